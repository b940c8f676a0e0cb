// Hand-written descriptors, each wrong in exactly one way chosen by one S2SIM_TEST_<VARIANT>
// definition, to test one refusal of the loader. Written without S2SIM_PLUGIN so that fields
// the macro always gets right can be wrong; still C-shaped and exported like the macro's.

#include <s2sim/plugin.hpp>

#include <cstddef>
#include <cstdint>

namespace {

// Never called: every variant is refused before any component is created. maybe_unused: the
// null_create / null_destroy variants do not reference them.
[[maybe_unused]] void* create_nothing(char* error, std::size_t size) {
  s2sim::detail::copy_error(error, size, "test plugin creates nothing");
  return nullptr;
}
[[maybe_unused]] void destroy_nothing(void*) {}

#ifdef S2SIM_TEST_NULL_CREATE
constexpr auto kCreate = static_cast<void* (*)(char*, std::size_t)>(nullptr);
#else
constexpr auto kCreate = &create_nothing;
#endif
#ifdef S2SIM_TEST_NULL_DESTROY
constexpr auto kDestroy = static_cast<void (*)(void*)>(nullptr);
#else
constexpr auto kDestroy = &destroy_nothing;
#endif
#if defined(S2SIM_TEST_EMPTY_KIND_NAME)
constexpr const char* kKindName = "";
#elif defined(S2SIM_TEST_NULL_KIND_NAME)
constexpr const char* kKindName = nullptr;
#else
constexpr const char* kKindName = "test_handwritten";
#endif
#ifdef S2SIM_TEST_BAD_CATEGORY
constexpr std::uint32_t kCategory = 99;
#else
constexpr std::uint32_t kCategory = static_cast<std::uint32_t>(s2sim::Category::sensor);
#endif

[[maybe_unused]] const s2sim_kind_entry kinds[] = {
    {kKindName, kCategory, kCreate, kDestroy},
#ifdef S2SIM_TEST_DUPLICATE_IN_PLUGIN
    {kKindName, kCategory, kCreate, kDestroy},
#endif
};

[[maybe_unused]] const s2sim_plugin_descriptor descriptor = {
#if defined(S2SIM_TEST_BAD_ABI)
    S2SIM_PLUGIN_ABI_VERSION + 1,
#elif defined(S2SIM_TEST_PREVIOUS_SDK)
    // As the previous SDK built it: its ABI, and an older SDK minor, which alone is accepted.
    S2SIM_PLUGIN_ABI_VERSION - 1,
#else
    S2SIM_PLUGIN_ABI_VERSION,
#endif
#ifdef S2SIM_TEST_BAD_STRUCT_SIZE
    // As an older, shorter descriptor would be: the kernel must not read past it.
    sizeof(s2sim_plugin_descriptor) - 8,
#else
    sizeof(s2sim_plugin_descriptor),
#endif
#ifdef S2SIM_TEST_BAD_KIND_ENTRY_SIZE
    sizeof(s2sim_kind_entry) + 8,
#else
    sizeof(s2sim_kind_entry),
#endif
#ifdef S2SIM_TEST_BAD_SDK_MAJOR
    S2SIM_SDK_VERSION_MAJOR + 1,
#else
    S2SIM_SDK_VERSION_MAJOR,
#endif
#if defined(S2SIM_TEST_BAD_SDK_MINOR)
    S2SIM_SDK_VERSION_MINOR + 1,
#elif defined(S2SIM_TEST_PREVIOUS_SDK)
    S2SIM_SDK_VERSION_MINOR - 1,
#else
    S2SIM_SDK_VERSION_MINOR,
#endif
    S2SIM_SDK_VERSION_PATCH,
#if defined(S2SIM_TEST_EMPTY_PLUGIN_NAME)
    "",
#elif defined(S2SIM_TEST_NULL_PLUGIN_NAME)
    nullptr,
#else
    "test_handwritten",
#endif
#ifdef S2SIM_TEST_NO_KINDS
    0,
#else
    static_cast<std::uint32_t>(sizeof(kinds) / sizeof(kinds[0])),
#endif
    kinds,
};

}  // namespace

extern "C" __attribute__((visibility("default"))) const s2sim_plugin_descriptor*
s2sim_plugin_descriptor_v1(void) {
#ifdef S2SIM_TEST_NULL_DESCRIPTOR
  return nullptr;
#else
  return &descriptor;
#endif
}
