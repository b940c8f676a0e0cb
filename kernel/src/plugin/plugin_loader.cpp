#include "plugin/plugin_loader.hpp"

#include "common/closest_names.hpp"

#include <s2sim/error.hpp>
#include <s2sim/version.hpp>

#include <boost/dll/runtime_symbol_info.hpp>
#include <boost/dll/shared_library.hpp>

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <set>
#include <system_error>
#include <utility>

namespace s2sim::plugin {

namespace fs = std::filesystem;

namespace {

using Library = boost::dll::shared_library;

[[noreturn]] void refuse(const fs::path& file, const std::string& message) {
  throw Error(ErrorKind::plugin, Location{file.string(), {}, {}}, message);
}

std::string version_string(std::uint32_t major, std::uint32_t minor, std::uint32_t patch) {
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
}

bool valid_category(std::uint32_t c) {
  return c >= static_cast<std::uint32_t>(Category::body) &&
         c <= static_cast<std::uint32_t>(Category::controller);
}

// Identity of a file for "same library" and "same folder" tests; falls back to the lexical
// form when the path cannot be resolved.
fs::path identity(const fs::path& p) {
  std::error_code ec;
  fs::path c = fs::weakly_canonical(p, ec);
  return ec ? p.lexically_normal() : c;
}

// Boost words a failed dlopen as "...load() failed (dlerror system message: TEXT): Bad file
// descriptor"; only TEXT tells the user anything.
std::string load_failure(const std::string& what) {
  const std::string tag = "(dlerror system message: ";
  const std::size_t start = what.find(tag);
  const std::size_t end = what.rfind("): ");
  if (start == std::string::npos || end == std::string::npos || end < start + tag.size()) {
    return what;
  }
  return "dlerror: " + what.substr(start + tag.size(), end - start - tag.size());
}

bool is_plugin_file_name(const std::string& name) {
  return name.size() >= 6 && name.rfind("lib", 0) == 0 &&
         name.compare(name.size() - 3, 3, ".so") == 0;
}

// A file that is a shared library by its name or its ELF header but is not named lib*.so:
// the scan skips it, and says so (a silently ignored library costs its author an hour).
bool looks_like_a_library(const fs::path& file) {
  const std::string name = file.filename().string();
  const bool so_name = (name.size() > 3 && name.compare(name.size() - 3, 3, ".so") == 0) ||
                       name.find(".so.") != std::string::npos;
  if (so_name) return true;
  char magic[4] = {};
  std::ifstream in(file, std::ios::binary);
  return in.read(magic, sizeof magic) && magic[0] == '\x7f' && magic[1] == 'E' && magic[2] == 'L' &&
         magic[3] == 'F';
}

// Whether `inner` lies inside the folder `outer` (both resolved).
bool is_inside(const fs::path& inner, const fs::path& outer) {
  const fs::path rel = identity(inner).lexically_relative(identity(outer));
  return !rel.empty() && *rel.begin() != "..";
}

// The file holding this code: the executable when the kernel is linked statically, the shared
// library (libs2sim.so) when it is linked dynamically. Its prefix holds the plugins.
fs::path kernel_binary() {
  std::error_code ec;
  fs::path here = boost::dll::this_line_location(ec);
  // For the executable itself dladdr gives argv[0] as typed ("s2sim-run" found on PATH): then
  // the executable's own path from /proc.
  if (ec || !here.is_absolute()) here = boost::dll::program_location(ec);
  return ec ? fs::path() : here;
}

}  // namespace

struct PluginRegistry::Impl {
  // One loaded, validated library.
  struct Loaded {
    fs::path file;
    std::string plugin_name;
    std::shared_ptr<Library> library;
  };
  struct Kind {
    KindInfo info;
    void* (*create)(char*, std::size_t);
    void (*destroy)(void*);
    std::shared_ptr<Loaded> loaded;
  };
  // A library whose descriptor passed validation but whose kinds are not registered yet.
  struct Candidate {
    std::shared_ptr<Loaded> loaded;
    std::vector<Kind> kinds;
  };

  std::vector<fs::path> search_path;
  bool scanned = false;
  std::map<fs::path, std::shared_ptr<Loaded>> libraries;  // by identity()
  std::map<std::string, Kind> kinds;
  std::vector<std::string> warnings;

  // Loads `file` and validates its descriptor; throws on any structural refusal. Registers
  // nothing, so a refused library leaves the registry unchanged (and is unloaded).
  static Candidate validate(const fs::path& file) {
    std::error_code ec;
    if (!fs::exists(file, ec)) refuse(file, "plugin library not found");
    if (!fs::is_regular_file(file, ec)) refuse(file, "plugin library is not a regular file");

    auto library = std::make_shared<Library>();
    try {
      // Local so two plugins' private symbols never interpose; lazy so an unused import does
      // not stop the descriptor from being read.
      library->load(file, boost::dll::load_mode::rtld_lazy | boost::dll::load_mode::rtld_local);
    } catch (const std::exception& e) {
      refuse(file, "not a loadable library: " + load_failure(e.what()));
    }
    if (!library->has(S2SIM_PLUGIN_ENTRY_SYMBOL)) {
      refuse(file, "no symbol '" S2SIM_PLUGIN_ENTRY_SYMBOL "': not an S2Sim plugin");
    }
    auto entry = library->get<const s2sim_plugin_descriptor*()>(S2SIM_PLUGIN_ENTRY_SYMBOL);
    const s2sim_plugin_descriptor* d = nullptr;
    try {
      d = entry();
    } catch (...) {
      refuse(file, "'" S2SIM_PLUGIN_ENTRY_SYMBOL "' threw an exception");
    }
    if (d == nullptr) refuse(file, "'" S2SIM_PLUGIN_ENTRY_SYMBOL "' returned a null descriptor");

    // The size first: no field past `struct_size` may be read before it is known to exist.
    // `abi_version` precedes it and is quoted because a new ABI usually explains a new size.
    if (d->struct_size != sizeof(s2sim_plugin_descriptor)) {
      std::string msg = "descriptor struct size " + std::to_string(d->struct_size) +
                        ", kernel expects " + std::to_string(sizeof(s2sim_plugin_descriptor));
      if (d->abi_version != S2SIM_PLUGIN_ABI_VERSION) {
        msg += " (plugin ABI version " + std::to_string(d->abi_version) + ", kernel's is " +
               std::to_string(S2SIM_PLUGIN_ABI_VERSION) + ")";
      }
      refuse(file, msg);
    }
    if (d->kind_entry_size != sizeof(s2sim_kind_entry)) {
      refuse(file, "kind entry size " + std::to_string(d->kind_entry_size) + ", kernel expects " +
                       std::to_string(sizeof(s2sim_kind_entry)));
    }
    if (d->abi_version != S2SIM_PLUGIN_ABI_VERSION) {
      refuse(file, "plugin ABI version " + std::to_string(d->abi_version) + ", kernel's is " +
                       std::to_string(S2SIM_PLUGIN_ABI_VERSION) +
                       ": rebuild the plugin against this SDK");
    }
    const std::string plugin_sdk =
        version_string(d->sdk_version_major, d->sdk_version_minor, d->sdk_version_patch);
    const std::string kernel_sdk =
        version_string(S2SIM_SDK_VERSION_MAJOR, S2SIM_SDK_VERSION_MINOR, S2SIM_SDK_VERSION_PATCH);
    if (d->sdk_version_major != S2SIM_SDK_VERSION_MAJOR) {
      refuse(file, "built against SDK " + plugin_sdk + ", kernel's SDK is " + kernel_sdk +
                       " (major versions differ)");
    }
    if (d->sdk_version_minor > S2SIM_SDK_VERSION_MINOR) {
      refuse(file,
             "built against SDK " + plugin_sdk + ", newer than the kernel's SDK " + kernel_sdk);
    }
    if (d->plugin_name == nullptr || d->plugin_name[0] == '\0') {
      refuse(file, "the descriptor has an empty plugin name");
    }
    const std::string plugin_name = d->plugin_name;
    const std::string who = "plugin '" + plugin_name + "'";
    if (d->kind_count == 0 || d->kinds == nullptr) refuse(file, who + " declares no kinds");

    Candidate c;
    c.loaded = std::make_shared<Loaded>(Loaded{file, plugin_name, library});
    std::set<std::string> seen;
    for (std::uint32_t i = 0; i < d->kind_count; ++i) {
      const s2sim_kind_entry& k = d->kinds[i];
      if (k.name == nullptr || k.name[0] == '\0') {
        refuse(file, who + ": kind #" + std::to_string(i) + " has an empty name");
      }
      const std::string name = k.name;
      const std::string kind = who + ": kind '" + name + "'";
      if (k.create == nullptr) refuse(file, kind + " has a null create function");
      if (k.destroy == nullptr) refuse(file, kind + " has a null destroy function");
      if (!valid_category(k.category)) {
        refuse(file, kind + " has unknown category " + std::to_string(k.category));
      }
      if (!seen.insert(name).second) refuse(file, kind + " is declared twice");
      c.kinds.push_back(Kind{KindInfo{name, static_cast<Category>(k.category), file, plugin_name},
                             k.create, k.destroy, c.loaded});
    }
    return c;
  }

  // Registers a validated library's kinds; throws, registering none, when another library
  // already provides one of them (an explicit load_library asks for exactly this file).
  void commit(Candidate c) {
    for (const Kind& k : c.kinds) {
      auto it = kinds.find(k.info.name);
      if (it != kinds.end()) {
        const KindInfo& other = it->second.info;
        refuse(c.loaded->file, "kind '" + k.info.name + "' of plugin '" + k.info.plugin_name +
                                   "' (" + c.loaded->file.string() +
                                   ") is already provided by plugin '" + other.plugin_name + "' (" +
                                   other.library.string() + ")");
      }
    }
    for (Kind& k : c.kinds) {
      std::string name = k.info.name;
      kinds.emplace(std::move(name), std::move(k));
    }
    libraries.emplace(identity(c.loaded->file), c.loaded);
  }

  // The scan's rule: the first library on the search path that provides a kind wins; a later
  // one's copy of that kind is skipped with a warning naming both files, its other kinds are
  // registered (a stale copy of a plugin must not stop every run).
  void commit_first_wins(Candidate c) {
    std::vector<Kind> fresh;
    for (Kind& k : c.kinds) {
      auto it = kinds.find(k.info.name);
      if (it == kinds.end()) {
        fresh.push_back(std::move(k));
        continue;
      }
      const KindInfo& first = it->second.info;
      warnings.push_back(c.loaded->file.string() + ": kind '" + k.info.name + "' of plugin '" +
                         k.info.plugin_name + "' ignored: plugin '" + first.plugin_name + "' (" +
                         first.library.string() +
                         ") provides it and comes first on the search path");
    }
    c.kinds = std::move(fresh);
    if (c.kinds.empty()) return;  // nothing of its own: not kept loaded
    commit(std::move(c));
  }

  void load(const fs::path& file) {
    if (libraries.count(identity(file)) != 0) return;  // already loaded: reuse it
    commit(validate(file));
  }

  void scan() {
    if (scanned) return;
    warnings.clear();
    for (const fs::path& folder : search_path) {
      std::error_code ec;
      std::vector<fs::path> files;
      std::vector<fs::path> misnamed;
      for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        std::error_code type_ec;
        if (!it->is_regular_file(type_ec)) continue;
        if (is_plugin_file_name(it->path().filename().string())) {
          files.push_back(it->path());
        } else if (looks_like_a_library(it->path())) {
          misnamed.push_back(it->path());
        }
      }
      std::sort(files.begin(), files.end());
      std::sort(misnamed.begin(), misnamed.end());
      for (const fs::path& file : misnamed)
        warnings.push_back(file.string() +
                           ": ignored: a plugin library's file name must be lib<name>.so");
      for (const fs::path& file : files) {
        if (libraries.count(identity(file)) != 0) continue;
        Candidate c;
        try {
          c = validate(file);
        } catch (const Error& e) {
          // An unrelated bad library must not stop the scan; it is reported instead.
          warnings.push_back(e.what());
          continue;
        }
        commit_first_wins(std::move(c));
      }
    }
    scanned = true;
  }

  // " (did you mean 'a' or 'b'?)" for the registered kinds close to `kind`, "" if none is.
  std::string did_you_mean(const std::string& kind) const {
    std::vector<std::string> names;
    for (const auto& entry : kinds)
      names.push_back(entry.first);
    // A kind within a third of its length in edits (at least 2): a typo, not another word.
    const std::size_t allowed = std::max<std::size_t>(2, kind.size() / 3);
    std::vector<std::string> close;
    for (const std::string& name : common::closest_names(kind, names, 3))
      if (common::edit_distance(kind, name) <= allowed) close.push_back(name);
    if (close.empty()) return "";
    std::string s = " (did you mean ";
    for (std::size_t i = 0; i < close.size(); ++i)
      s += (i == 0 ? "'" : i + 1 == close.size() ? " or '" : ", '") + close[i] + "'";
    return s + "?)";
  }

  std::string describe_search() const {
    std::string s = "searched:";
    if (search_path.empty()) s += " (no folders)";
    for (const fs::path& folder : search_path) {
      std::error_code ec;
      s += "\n  " + folder.string() + (fs::is_directory(folder, ec) ? "" : " (missing)");
    }
    if (!warnings.empty()) {
      s += "\nlibraries skipped:";
      for (const std::string& w : warnings)
        s += "\n  " + w;
    }
    return s;
  }
};

std::vector<fs::path> PluginRegistry::default_search_path() {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("S2SIM_PLUGIN_PATH")) {
    std::string value = env;
    std::size_t start = 0;
    while (start <= value.size()) {
      std::size_t end = value.find(':', start);
      if (end == std::string::npos) end = value.size();
      if (end > start) candidates.emplace_back(value.substr(start, end - start));
      start = end + 1;
    }
  }
  // The kernel's own prefix: <prefix>/bin/s2sim-run or <prefix>/lib/libs2sim.so both reach
  // <prefix>/lib/s2sim/plugins; the build tree's bin/ and lib/ reach build/plugins.
  const fs::path binary = kernel_binary();
  if (!binary.empty()) {
    const fs::path dir = binary.parent_path();
    candidates.push_back((dir / ".." / "lib" / "s2sim" / "plugins").lexically_normal());
    candidates.push_back((dir / ".." / "plugins").lexically_normal());
  }
#ifdef S2SIM_BUILD_PLUGIN_DIR
  // The build tree's plugin folder only for a binary that is itself in the build tree (a test
  // or a module built elsewhere in it); an installed binary never looks there.
  const fs::path build_plugins(S2SIM_BUILD_PLUGIN_DIR);
  if (!binary.empty() && is_inside(binary, build_plugins.parent_path())) {
    candidates.push_back(build_plugins);
  }
#endif

  std::vector<fs::path> result;
  std::set<fs::path> seen;
  for (const fs::path& c : candidates) {
    std::error_code dir_ec;
    if (!fs::is_directory(c, dir_ec)) continue;
    if (seen.insert(identity(c)).second) result.push_back(c);
  }
  return result;
}

std::vector<fs::path> PluginRegistry::search_path(const std::vector<fs::path>& first,
                                                  bool with_defaults) {
  std::vector<fs::path> result;
  std::set<fs::path> seen;
  auto add = [&](const fs::path& p) {
    if (seen.insert(identity(p)).second) result.push_back(p);
  };
  for (const fs::path& p : first)
    add(p);
  if (with_defaults)
    for (const fs::path& p : default_search_path())
      add(p);
  return result;
}

PluginRegistry::PluginRegistry(std::vector<fs::path> search_path)
    : impl_(std::make_shared<Impl>()) {
  impl_->search_path = std::move(search_path);
}

void PluginRegistry::load_library(const fs::path& file) {
  impl_->load(file);
}

const KindInfo& PluginRegistry::find(const std::string& kind) {
  impl_->scan();
  auto it = impl_->kinds.find(kind);
  if (it == impl_->kinds.end()) {
    throw Error(ErrorKind::plugin, "no plugin provides kind '" + kind + "'" +
                                       impl_->did_you_mean(kind) + "; " + impl_->describe_search());
  }
  return it->second.info;
}

bool PluginRegistry::has(const std::string& kind) {
  impl_->scan();
  return impl_->kinds.count(kind) != 0;
}

ComponentPtr PluginRegistry::create(const std::string& kind) {
  find(kind);  // scans, and throws with the search details when the kind is unknown
  const Impl::Kind& k = impl_->kinds.at(kind);
  char error[1024] = {};
  void* made = k.create(error, sizeof(error));
  if (made == nullptr) {
    error[sizeof(error) - 1] = '\0';  // do not trust the plugin to terminate it
    throw Error(ErrorKind::plugin, "plugin '" + k.info.plugin_name + "' (" +
                                       k.info.library.string() + "): creating kind '" + kind +
                                       "' failed: " + (error[0] ? error : "no message given"));
  }
  return ComponentPtr(static_cast<Component*>(made), k.destroy, k.loaded->library);
}

const std::vector<std::string>& PluginRegistry::scan_warnings() const {
  return impl_->warnings;
}

std::vector<KindInfo> PluginRegistry::kinds() {
  impl_->scan();
  std::vector<KindInfo> out;
  out.reserve(impl_->kinds.size());
  for (const auto& [name, k] : impl_->kinds)
    out.push_back(k.info);
  return out;
}

}  // namespace s2sim::plugin
