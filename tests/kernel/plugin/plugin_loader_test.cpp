#include "plugin/plugin_loader.hpp"

#include <s2sim/error.hpp>
#include <s2sim/plugin.hpp>
#include <s2sim/version.hpp>

#include <dlfcn.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using s2sim::Error;
using s2sim::ErrorKind;
using s2sim::plugin::PluginRegistry;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {

// A registry that scans nothing: only explicitly loaded libraries.
const std::vector<fs::path> kNoFolders;

fs::path folder(const std::string& name) {
  return fs::path(S2SIM_TEST_PLUGIN_DIR) / name;
}
// Every test plugin is test-plugins/<folder>/lib<name>.so; refused ones have name == folder.
fs::path library(const std::string& dir, const std::string& name) {
  return folder(dir) / ("lib" + name + ".so");
}
fs::path library(const std::string& name) {
  return library(name, name);
}

// The message of the s2sim::Error (kind plugin) that `f` throws; fails the test otherwise.
template <class F>
std::string plugin_error(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::plugin) << e.what();
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an s2sim::Error: " << e.what();
    return e.what();
  }
  ADD_FAILURE() << "did not throw";
  return {};
}

std::string version(int major, int minor, int patch) {
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
}

// The good plugin's count of live components, read through its test hook; nullopt when the
// library is not loaded any more.
std::optional<int> live_components(const fs::path& lib) {
  void* handle = dlopen(lib.c_str(), RTLD_NOW | RTLD_NOLOAD);
  if (handle == nullptr) return std::nullopt;
  auto hook = reinterpret_cast<int (*)()>(dlsym(handle, "s2sim_test_live_components"));
  std::optional<int> n;
  if (hook != nullptr) n = hook();
  dlclose(handle);  // drops only the reference RTLD_NOLOAD just took
  return n;
}

// One refusal: the test plugin (in its own folder) and what the message must say.
struct Refusal {
  std::string name;
  std::vector<std::string> reasons;
};

std::ostream& operator<<(std::ostream& os, const Refusal& r) {
  return os << r.name;
}

std::vector<Refusal> refusals() {
  const std::string kernel_sdk = s2sim::kSdkVersionString;
  const std::string kind = "plugin 'test_handwritten': kind 'test_handwritten'";
  return {
      {"not_a_library", {"not a loadable library: dlerror: ", "invalid ELF header"}},
      {"no_descriptor", {"no symbol 's2sim_plugin_descriptor_v1': not an S2Sim plugin"}},
      {"null_descriptor", {"'s2sim_plugin_descriptor_v1' returned a null descriptor"}},
      {"bad_abi",
       {"plugin ABI version " + std::to_string(S2SIM_PLUGIN_ABI_VERSION + 1) + ", kernel's is " +
        std::to_string(S2SIM_PLUGIN_ABI_VERSION)}},
      // A plugin built with the SDK before this one: its ABI no longer matches.
      {"previous_sdk",
       {"plugin ABI version " + std::to_string(S2SIM_PLUGIN_ABI_VERSION - 1) + ", kernel's is " +
            std::to_string(S2SIM_PLUGIN_ABI_VERSION),
        "rebuild the plugin against this SDK"}},
      {"bad_struct_size",
       {"descriptor struct size " + std::to_string(sizeof(s2sim_plugin_descriptor) - 8) +
        ", kernel expects " + std::to_string(sizeof(s2sim_plugin_descriptor))}},
      {"bad_kind_entry_size",
       {"kind entry size " + std::to_string(sizeof(s2sim_kind_entry) + 8) + ", kernel expects " +
        std::to_string(sizeof(s2sim_kind_entry))}},
      {"bad_sdk_major",
       {"SDK " +
            version(S2SIM_SDK_VERSION_MAJOR + 1, S2SIM_SDK_VERSION_MINOR, S2SIM_SDK_VERSION_PATCH),
        kernel_sdk, "major versions differ"}},
      {"bad_sdk_minor",
       {"SDK " +
            version(S2SIM_SDK_VERSION_MAJOR, S2SIM_SDK_VERSION_MINOR + 1, S2SIM_SDK_VERSION_PATCH),
        "newer than the kernel's SDK " + kernel_sdk}},
      {"empty_plugin_name", {"empty plugin name"}},
      {"null_plugin_name", {"empty plugin name"}},
      {"empty_kind_name", {"plugin 'test_handwritten': kind #0 has an empty name"}},
      {"null_kind_name", {"plugin 'test_handwritten': kind #0 has an empty name"}},
      {"no_kinds", {"plugin 'test_handwritten' declares no kinds"}},
      {"null_create", {kind + " has a null create function"}},
      {"null_destroy", {kind + " has a null destroy function"}},
      {"bad_category", {kind + " has unknown category 99"}},
      {"duplicate_in_plugin", {kind + " is declared twice"}},
  };
}

class RefusalTest : public ::testing::TestWithParam<Refusal> {};

TEST_P(RefusalTest, ExplicitLoadThrowsNamingFileAndReason) {
  const Refusal& r = GetParam();
  PluginRegistry registry(kNoFolders);
  const std::string message = plugin_error([&] { registry.load_library(library(r.name)); });
  EXPECT_THAT(message, HasSubstr(library(r.name).string()));
  for (const std::string& reason : r.reasons)
    EXPECT_THAT(message, HasSubstr(reason));
  EXPECT_TRUE(registry.kinds().empty());  // a refused library registers nothing
}

TEST_P(RefusalTest, ScanSkipsWithWarning) {
  const Refusal& r = GetParam();
  PluginRegistry registry({folder(r.name)});
  EXPECT_FALSE(registry.has("test_handwritten"));
  ASSERT_EQ(registry.scan_warnings().size(), 1u);
  const std::string& warning = registry.scan_warnings()[0];
  EXPECT_THAT(warning, HasSubstr(library(r.name).string()));
  for (const std::string& reason : r.reasons)
    EXPECT_THAT(warning, HasSubstr(reason));
}

INSTANTIATE_TEST_SUITE_P(EachRefusal, RefusalTest, ::testing::ValuesIn(refusals()),
                         [](const auto& p) { return p.param.name; });

TEST(PluginLoader, MissingFileThrows) {
  PluginRegistry registry(kNoFolders);
  const fs::path file = folder("good") / "libdoes_not_exist.so";
  EXPECT_THAT(plugin_error([&] { registry.load_library(file); }),
              AllOf(HasSubstr(file.string()), HasSubstr("not found")));
}

TEST(PluginLoader, LoadsGoodPluginAndDescribesItsKinds) {
  PluginRegistry registry(kNoFolders);
  registry.load_library(library("good"));
  const std::vector<s2sim::plugin::KindInfo> kinds = registry.kinds();
  ASSERT_EQ(kinds.size(), 2u);
  EXPECT_EQ(kinds[0].name, "test_counter");
  EXPECT_EQ(kinds[0].category, s2sim::Category::sensor);
  EXPECT_EQ(kinds[0].plugin_name, "test_good");
  EXPECT_EQ(kinds[0].library, library("good"));
  EXPECT_EQ(kinds[1].name, "test_throwing_factory");
  EXPECT_EQ(kinds[1].category, s2sim::Category::actuator);
  EXPECT_TRUE(registry.scan_warnings().empty());
}

TEST(PluginLoader, LoadingTheSameFileTwiceReusesIt) {
  PluginRegistry registry(kNoFolders);
  registry.load_library(library("good"));
  registry.load_library(library("good"));
  // Another spelling of the same file is the same library, not a second claim on its kinds.
  registry.load_library(folder("good") / ".." / "good" / "libgood.so");
  EXPECT_EQ(registry.kinds().size(), 2u);
}

TEST(PluginLoader, ExplicitLoadAfterScanOfSameFileIsANoOp) {
  PluginRegistry registry({folder("good")});
  EXPECT_TRUE(registry.has("test_counter"));
  registry.load_library(library("good"));
  EXPECT_EQ(registry.kinds().size(), 2u);
}

TEST(PluginLoader, KindClaimedByAnotherLibraryIsRefusedNamingBoth) {
  PluginRegistry registry(kNoFolders);
  registry.load_library(library("good"));
  const std::string message =
      plugin_error([&] { registry.load_library(library("duplicate_kind")); });
  EXPECT_THAT(message, AllOf(HasSubstr(library("good").string()),
                             HasSubstr(library("duplicate_kind").string()),
                             HasSubstr("kind 'test_counter'")));
  // The refused library changed nothing.
  EXPECT_EQ(registry.find("test_counter").library, library("good"));
  EXPECT_EQ(registry.find("test_counter").plugin_name, "test_good");
}

TEST(PluginLoader, ScanOfMixedFolderRegistersGoodAndWarnsAboutBad) {
  PluginRegistry registry({folder("mixed")});
  EXPECT_TRUE(registry.has("test_mixed_counter"));
  EXPECT_EQ(registry.find("test_mixed_counter").library, library("mixed", "mixed_good"));
  ASSERT_EQ(registry.scan_warnings().size(), 1u);
  EXPECT_THAT(registry.scan_warnings()[0],
              AllOf(HasSubstr(library("mixed", "mixed_bad_abi").string()),
                    HasSubstr("plugin ABI version")));
}

TEST(PluginLoader, ScanWithDuplicateKindsAcrossFoldersFirstWinsWithAWarningNamingBoth) {
  // A stale copy of a plugin later on the path must not stop every run.
  PluginRegistry registry({folder("good"), folder("duplicate_kind")});
  ASSERT_TRUE(registry.has("test_counter"));
  EXPECT_EQ(registry.find("test_counter").library, library("good"));
  EXPECT_EQ(registry.find("test_counter").plugin_name, "test_good");
  ASSERT_EQ(registry.scan_warnings().size(), 1u);
  EXPECT_THAT(
      registry.scan_warnings()[0],
      AllOf(HasSubstr(library("good").string()), HasSubstr(library("duplicate_kind").string()),
            HasSubstr("kind 'test_counter'"), HasSubstr("comes first")));

  // The other order: the other library wins.
  PluginRegistry reversed({folder("duplicate_kind"), folder("good")});
  EXPECT_EQ(reversed.find("test_counter").library, library("duplicate_kind"));
  EXPECT_EQ(reversed.find("test_counter").plugin_name, "test_duplicate");
  // The later library's other kinds are registered: only the duplicate is skipped.
  EXPECT_TRUE(reversed.has("test_throwing_factory"));
  EXPECT_EQ(reversed.find("test_throwing_factory").library, library("good"));
}

TEST(PluginLoader, LibraryNotNamedLibSoIsSkippedWithAWarningSayingWhy) {
  // test-plugins/misnamed/misnamed.so is a valid plugin under a name the scan does not load.
  PluginRegistry registry({folder("misnamed")});
  EXPECT_FALSE(registry.has("test_misnamed_counter"));
  ASSERT_EQ(registry.scan_warnings().size(), 1u);
  EXPECT_THAT(registry.scan_warnings()[0],
              AllOf(HasSubstr((folder("misnamed") / "misnamed.so").string()), HasSubstr("ignored"),
                    HasSubstr("lib<name>.so")));
  EXPECT_THAT(plugin_error([&] { registry.find("test_misnamed_counter"); }),
              HasSubstr("misnamed.so: ignored"));
}

TEST(PluginLoader, UnknownKindSuggestsTheCloseKinds) {
  PluginRegistry registry({folder("good")});
  EXPECT_THAT(plugin_error([&] { registry.find("test_countr"); }),
              AllOf(HasSubstr("no plugin provides kind 'test_countr'"),
                    HasSubstr("did you mean 'test_counter'?")));
  // Nothing close: no suggestion.
  EXPECT_THAT(plugin_error([&] { registry.find("warp_drive"); }), Not(HasSubstr("did you mean")));
}

TEST(PluginLoader, UnknownKindListsFoldersSearchedAndWarnings) {
  const fs::path missing = folder("no_such_folder");
  PluginRegistry registry({folder("mixed"), missing});
  EXPECT_FALSE(registry.has("test_warp_drive"));  // has() never throws for a missing kind
  const std::string message = plugin_error([&] { registry.find("test_warp_drive"); });
  EXPECT_THAT(message, AllOf(HasSubstr("'test_warp_drive'"), HasSubstr(folder("mixed").string()),
                             HasSubstr(missing.string()),
                             HasSubstr(library("mixed", "mixed_bad_abi").string()),
                             HasSubstr("plugin ABI version")));
  EXPECT_THAT(plugin_error([&] { registry.create("test_warp_drive"); }),
              HasSubstr("'test_warp_drive'"));
}

TEST(PluginLoader, ScanIgnoresMissingFoldersAndNonPluginFiles) {
  // The source folder holds .cpp and .txt files, none named lib*.so.
  PluginRegistry registry({folder("no_such_folder"),
                           fs::path(S2SIM_SOURCE_DIR) / "tests" / "plugins" / "test_plugins"});
  EXPECT_TRUE(registry.kinds().empty());
  EXPECT_TRUE(registry.scan_warnings().empty());
}

TEST(PluginLoader, CreateReturnsComponentDestroyedCleanly) {
  const fs::path lib = library("good");
  {
    PluginRegistry registry({folder("good")});
    s2sim::plugin::ComponentPtr c = registry.create("test_counter");
    ASSERT_TRUE(c);
    EXPECT_NE(c.get(), nullptr);
    EXPECT_EQ(live_components(lib), 1);

    s2sim::plugin::ComponentPtr moved = std::move(c);
    EXPECT_FALSE(c);
    EXPECT_EQ(live_components(lib), 1);
    moved = s2sim::plugin::ComponentPtr();
    EXPECT_EQ(live_components(lib), 0);
  }
}

TEST(PluginLoader, ComponentKeepsItsLibraryLoaded) {
  const fs::path lib = library("good");
  s2sim::plugin::ComponentPtr c;
  {
    PluginRegistry registry(kNoFolders);
    registry.load_library(lib);
    c = registry.create("test_counter");
  }
  // The registry is gone; the component's code must still be mapped.
  EXPECT_EQ(live_components(lib), 1);
  c = s2sim::plugin::ComponentPtr();  // destroy runs before the library is released
  // The last user gone, the library is unloaded: the check above was not vacuous.
  EXPECT_EQ(live_components(lib), std::nullopt);
}

TEST(PluginLoader, FactoryFailureMessageReachesTheException) {
  PluginRegistry registry({folder("good")});
  const std::string message = plugin_error([&] { registry.create("test_throwing_factory"); });
  EXPECT_THAT(message, AllOf(HasSubstr("plugin 'test_good'"), HasSubstr(library("good").string()),
                             HasSubstr("creating kind 'test_throwing_factory' failed"),
                             HasSubstr("thruster needs a propeller")));
}

// Sets an environment variable for one scope and restores it.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_) {
      setenv(name_, old_->c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(PluginLoader, DefaultSearchPathHonoursEnvironment) {
  const fs::path missing = folder("no_such_folder");
  ScopedEnv env("S2SIM_PLUGIN_PATH", folder("good").string() + "::" + missing.string() + ":" +
                                         folder("mixed").string() + ":" + folder("good").string() +
                                         ":");
  const std::vector<fs::path> path = PluginRegistry::default_search_path();
  ASSERT_GE(path.size(), 2u);
  EXPECT_EQ(path[0], folder("good"));
  EXPECT_EQ(path[1], folder("mixed"));
  std::set<fs::path> seen;
  for (const fs::path& p : path) {
    EXPECT_NE(p, missing);
    EXPECT_TRUE(fs::is_directory(p)) << p;
    EXPECT_TRUE(seen.insert(fs::canonical(p)).second) << "listed twice: " << p;
  }

  PluginRegistry registry;  // uses default_search_path()
  EXPECT_TRUE(registry.has("test_counter"));
  EXPECT_TRUE(registry.has("test_mixed_counter"));
}

TEST(PluginLoader, DefaultSearchPathWithoutEnvironmentHasNoTestFolders) {
  ScopedEnv env("S2SIM_PLUGIN_PATH", "");
  for (const fs::path& p : PluginRegistry::default_search_path()) {
    EXPECT_THAT(p.string(), Not(HasSubstr(S2SIM_TEST_PLUGIN_DIR)));
  }
}

TEST(PluginLoader, SearchPathPutsTheGivenFoldersFirstThenTheDefaults) {
  ScopedEnv env("S2SIM_PLUGIN_PATH", folder("mixed").string());
  const std::vector<fs::path> path = PluginRegistry::search_path({folder("good"), folder("mixed")});
  ASSERT_GE(path.size(), 2u);
  EXPECT_EQ(path[0], folder("good"));
  EXPECT_EQ(path[1], folder("mixed"));  // listed once, where it first comes
  EXPECT_EQ(std::count(path.begin(), path.end(), folder("mixed")), 1);
  // This test binary lies in the build tree: the build's plugin folder is a default.
  EXPECT_NE(std::find(path.begin(), path.end(), fs::path(S2SIM_PLUGIN_DIR)), path.end());
  // Without the defaults, only the folders given.
  EXPECT_EQ(PluginRegistry::search_path({folder("good")}, false),
            std::vector<fs::path>{folder("good")});
}

}  // namespace
