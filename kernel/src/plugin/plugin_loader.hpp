#pragma once
/// \file
/// Finds and loads plugin libraries (Boost.DLL) and creates components by kind name.

#include <s2sim/component.hpp>
#include <s2sim/plugin.hpp>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace s2sim::plugin {

/// A created component with the library that made it kept alive as long as it lives.
class ComponentPtr {
 public:
  ComponentPtr() = default;
  ComponentPtr(Component* c, void (*destroy)(void*), std::shared_ptr<void> library)
      : component_(c), destroy_(destroy), library_(std::move(library)) {}
  ComponentPtr(ComponentPtr&& o) noexcept { *this = std::move(o); }
  ComponentPtr& operator=(ComponentPtr&& o) noexcept {
    reset();
    component_ = o.component_;
    destroy_ = o.destroy_;
    library_ = std::move(o.library_);
    o.component_ = nullptr;
    return *this;
  }
  ComponentPtr(const ComponentPtr&) = delete;
  ComponentPtr& operator=(const ComponentPtr&) = delete;
  ~ComponentPtr() { reset(); }

  Component* get() const { return component_; }
  Component* operator->() const { return component_; }
  explicit operator bool() const { return component_ != nullptr; }

 private:
  void reset() {
    if (component_ != nullptr) destroy_(component_);  // before the library is released
    component_ = nullptr;
  }
  Component* component_ = nullptr;
  void (*destroy_)(void*) = nullptr;
  std::shared_ptr<void> library_;  // a boost::dll::shared_library, type-erased
};

/// What is known of one kind after scanning.
struct KindInfo {
  std::string name;
  Category category;
  std::filesystem::path library;
  std::string plugin_name;
};

/// Scans folders for plugin libraries (`lib*.so`), loading each only to read its
/// descriptor, and creates components by kind name. Every refusal throws `s2sim::Error` of kind
/// `plugin` whose message names the library file and the reason: no descriptor symbol, ABI or
/// SDK version mismatch, struct-size mismatch, a kind already provided (explicit load only),
/// unknown kind (with the close kind names), a factory that fails. While scanning, a refused
/// library, a library not named lib*.so and a kind that an earlier library on the path
/// already provides (the first wins) are skipped with a warning.
class PluginRegistry {
 public:
  /// The default search path: every folder of the environment variable S2SIM_PLUGIN_PATH
  /// (':'-separated), then the kernel's own prefix: `<dir>/../lib/s2sim/plugins` and
  /// `<dir>/../plugins`, where `<dir>` holds the binary the kernel is in (the executable, or
  /// libs2sim.so); the build tree's plugin folder only for a binary inside the build tree.
  /// Missing folders and repeats are left out.
  static std::vector<std::filesystem::path> default_search_path();
  /// `first` (e.g. `--plugin-path` folders), then default_search_path() unless
  /// `with_defaults` is false; repeats left out.
  static std::vector<std::filesystem::path> search_path(
      const std::vector<std::filesystem::path>& first, bool with_defaults = true);

  explicit PluginRegistry(std::vector<std::filesystem::path> search_path = default_search_path());

  /// Loads one library explicitly and registers its kinds (throws on any refusal).
  void load_library(const std::filesystem::path& file);

  /// The kind's info, scanning the search path on first use. Throws (kind plugin) when no
  /// plugin provides it, listing the folders searched.
  const KindInfo& find(const std::string& kind);
  /// Whether some plugin provides `kind` (scans on first use; never throws for a missing kind).
  bool has(const std::string& kind);

  /// Creates a component of `kind`. Throws when the kind is unknown or its factory fails.
  ComponentPtr create(const std::string& kind);

  /// Files and kinds skipped while scanning, with the reason (the runner prints them).
  /// Does not scan by itself: empty until the first `find`/`has`/`create`/`kinds`.
  const std::vector<std::string>& scan_warnings() const;
  /// Every registered kind.
  std::vector<KindInfo> kinds();

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace s2sim::plugin
