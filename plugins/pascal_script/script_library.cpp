#include "script_library.hpp"

#include <dlfcn.h>
#include <unistd.h>
#include <cfenv>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace s2sim::pascal {
namespace {

/// Masks every floating-point exception for its lifetime and restores the caller's
/// environment (flags and masks, x87 and SSE) afterwards.
class FpuGuard {
 public:
  FpuGuard() { std::feholdexcept(&saved_); }
  ~FpuGuard() { std::fesetenv(&saved_); }

 private:
  std::fenv_t saved_{};
};

}  // namespace

ScriptLibrary::~ScriptLibrary() {
  unload();
}

void ScriptLibrary::unload() {
  if (handle_) {
    FpuGuard guard;
    ::dlclose(handle_);
  }
  handle_ = nullptr;
  run_ = nullptr;
  if (!copy_.empty()) {
    std::error_code ec;
    std::filesystem::remove(copy_, ec);
    copy_.clear();
  }
}

void ScriptLibrary::load(const std::filesystem::path& library, const HostTable& table,
                         std::int32_t seed) {
  unload();
  // A private copy: dlopen of the same path would share the script's globals.
  std::string tmpl = (std::filesystem::temp_directory_path() / "s2sim-script-XXXXXX").string();
  const int fd = ::mkstemp(tmpl.data());
  if (fd < 0) throw std::runtime_error("cannot create a temporary copy of " + library.string());
  ::close(fd);
  std::filesystem::copy_file(library, tmpl, std::filesystem::copy_options::overwrite_existing);
  {
    FpuGuard guard;  // the Pascal RTL's start-up sets its own FPU masks
    handle_ = ::dlopen(tmpl.c_str(), RTLD_NOW | RTLD_LOCAL);
  }
  // Kept while loaded: addr2line reads its line table (fpc -g) from the file on an error.
  copy_ = tmpl;
  if (!handle_)
    throw std::runtime_error(std::string("cannot load the compiled script: ") + ::dlerror());
  auto bind =
      reinterpret_cast<void (*)(const HostTable*, std::int32_t)>(::dlsym(handle_, "s2s_bind"));
  run_ = reinterpret_cast<int (*)(std::int32_t, double, char*, std::int32_t)>(
      ::dlsym(handle_, "s2s_run"));
  if (!bind || !run_) {
    unload();
    throw std::runtime_error("the compiled script lacks its entry points (s2s_bind, s2s_run)");
  }
  table_ = table;
  FpuGuard guard;
  bind(&table_, seed);
}

std::string ScriptLibrary::describe(std::uintptr_t address) const {
  Dl_info info{};
  if (!handle_ || ::dladdr(reinterpret_cast<void*>(address), &info) == 0 || !info.dli_fbase)
    return {};
  if (std::filesystem::path(info.dli_fname) != copy_) return {};  // not the script's code
  char offset[32];
  std::snprintf(
      offset, sizeof offset, "0x%lx",
      static_cast<unsigned long>(address - reinterpret_cast<std::uintptr_t>(info.dli_fbase) - 1));
  const std::string command = "addr2line -f -e '" + copy_.string() + "' " + offset + " 2>/dev/null";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return {};
  char routine[512] = {0}, where[1024] = {0};
  const bool ok =
      std::fgets(routine, sizeof routine, pipe) && std::fgets(where, sizeof where, pipe);
  ::pclose(pipe);
  if (!ok) return {};
  std::string r = routine, w = where;
  while (!r.empty() && (r.back() == '\n' || r.back() == '\r'))
    r.pop_back();
  while (!w.empty() && (w.back() == '\n' || w.back() == '\r'))
    w.pop_back();
  if (w.rfind("??", 0) == 0) return {};
  // FPC's symbol names read P$S2SCRIPT_$$_CONTROL: keep the routine.
  if (const auto dollar = r.rfind("$$_"); dollar != std::string::npos) r = r.substr(dollar + 3);
  if (const auto d = w.find(" (discriminator"); d != std::string::npos) w = w.substr(0, d);
  return r + " at " + w;
}

bool ScriptLibrary::run(int which, double now_s, std::string& error) {
  char message[2048] = {0};
  int status = 0;
  {
    FpuGuard guard;
    status = run_(which, now_s, message, static_cast<std::int32_t>(sizeof message));
  }
  if (status == 0) return true;
  error = message;
  return false;
}

}  // namespace s2sim::pascal
