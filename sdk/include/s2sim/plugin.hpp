#pragma once
/// \file
/// The plugin boundary. A plugin is a shared library exporting one C function,
/// `s2sim_plugin_descriptor_v1`, that returns a C-shaped descriptor: versions, struct sizes,
/// the plugin's name and its kinds, each with a create and a destroy function.
///
/// What crosses the boundary, in two layers:
/// - The descriptor and the kind entries are C: plain integers, `const char*` and function
///   pointers, no `std::` type, no exception (create() turns one into an error message). The
///   kernel reads them from any plugin, checks `struct_size`, `kind_entry_size`, the ABI
///   version and the SDK version, and refuses a mismatch with a message.
/// - A created component is an `s2sim::Component` and talks to the kernel through C++
///   interfaces (`Component`, `ConfigureContext`, `StepContext`, `Params`) whose calls pass
///   `std::string`, `std::string_view`, `std::vector`, `std::initializer_list` and throw
///   `s2sim::Error`. Their layout is that of the compiler and standard library that built each
///   side, which no version number captures: a plugin must be built with the same compiler and
///   standard library (and the same library ABI settings) as the kernel. The version check
///   guarantees the same SDK headers (vtable order, `detail::WorldView` layout); the toolchain
///   rule, which the kernel cannot check, guarantees the `std::` types agree.
///
/// Writing a plugin:
/// \code
///   #include <s2sim/plugin.hpp>
///   class Thruster : public s2sim::Component { ... };
///   S2SIM_PLUGIN("my_plugins",
///                S2SIM_KIND("thruster", s2sim::Category::actuator, Thruster));
/// \endcode

#include <s2sim/component.hpp>
#include <s2sim/version.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <new>

extern "C" {

/// One component kind a plugin provides.
typedef struct s2sim_kind_entry {
  /// Name used in scenes (`<plugin kind='...'>`), unique across all loaded plugins.
  const char* name;
  /// An `s2sim::Category` value.
  std::uint32_t category;
  /// Creates a component (an `s2sim::Component*`). On failure returns NULL and writes a
  /// NUL-terminated message of at most `error_size` bytes into `error`.
  void* (*create)(char* error, std::size_t error_size);
  /// Destroys what `create` returned.
  void (*destroy)(void* component);
} s2sim_kind_entry;

/// What a plugin library describes of itself.
typedef struct s2sim_plugin_descriptor {
  std::uint32_t abi_version;      ///< S2SIM_PLUGIN_ABI_VERSION the plugin was built with
  std::uint32_t struct_size;      ///< sizeof(s2sim_plugin_descriptor) in the plugin
  std::uint32_t kind_entry_size;  ///< sizeof(s2sim_kind_entry) in the plugin
  std::uint32_t sdk_version_major;
  std::uint32_t sdk_version_minor;
  std::uint32_t sdk_version_patch;
  const char* plugin_name;
  std::uint32_t kind_count;
  const s2sim_kind_entry* kinds;
} s2sim_plugin_descriptor;

/// Signature of the exported entry point.
typedef const s2sim_plugin_descriptor* (*s2sim_plugin_entry_fn)(void);
}

/// Name of the exported entry point.
#define S2SIM_PLUGIN_ENTRY_SYMBOL "s2sim_plugin_descriptor_v1"

namespace s2sim::detail {

inline void copy_error(char* error, std::size_t size, const char* message) {
  if (error == nullptr || size == 0) return;
  std::strncpy(error, message, size - 1);
  error[size - 1] = '\0';
}

/// Creates a T; turns any exception into an error message so none crosses the C boundary.
template <class T>
void* create_component(char* error, std::size_t error_size) noexcept {
  try {
    return static_cast<Component*>(new T());
  } catch (const std::exception& e) {
    copy_error(error, error_size, e.what());
  } catch (...) {
    copy_error(error, error_size, "unknown exception");
  }
  return nullptr;
}

template <class T>
void destroy_component(void* component) noexcept {
  delete static_cast<T*>(static_cast<Component*>(component));
}

}  // namespace s2sim::detail

#if defined(_WIN32)
#define S2SIM_EXPORT __declspec(dllexport)
#else
#define S2SIM_EXPORT __attribute__((visibility("default")))
#endif

/// One kind entry for S2SIM_PLUGIN: scene name, `s2sim::Category`, component class.
#define S2SIM_KIND(name, category, Type)                                                  \
  s2sim_kind_entry {                                                                      \
    name, static_cast<std::uint32_t>(category), &::s2sim::detail::create_component<Type>, \
        &::s2sim::detail::destroy_component<Type>                                         \
  }

/// Defines the plugin's descriptor and its exported entry point.
#define S2SIM_PLUGIN(plugin_name, ...)                                                      \
  namespace {                                                                               \
  const s2sim_kind_entry s2sim_plugin_kinds_[] = {__VA_ARGS__};                             \
  const s2sim_plugin_descriptor s2sim_plugin_descriptor_ = {                                \
      S2SIM_PLUGIN_ABI_VERSION,                                                             \
      sizeof(s2sim_plugin_descriptor),                                                      \
      sizeof(s2sim_kind_entry),                                                             \
      S2SIM_SDK_VERSION_MAJOR,                                                              \
      S2SIM_SDK_VERSION_MINOR,                                                              \
      S2SIM_SDK_VERSION_PATCH,                                                              \
      plugin_name,                                                                          \
      static_cast<std::uint32_t>(sizeof(s2sim_plugin_kinds_) / sizeof(s2sim_kind_entry)),   \
      s2sim_plugin_kinds_};                                                                 \
  }                                                                                         \
  extern "C" S2SIM_EXPORT const s2sim_plugin_descriptor* s2sim_plugin_descriptor_v1(void) { \
    return &s2sim_plugin_descriptor_;                                                       \
  }
