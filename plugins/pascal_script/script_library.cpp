#include "script_library.hpp"

#include <dlfcn.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cfenv>
#include <chrono>
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
  copy_.clear();
}

namespace {

constexpr const char* kCopyPrefix = "s2sim-script-";

/// Copies that a process killed between its copy and its load left behind (the load removes
/// its own at once): ours by name, owner and age.
void remove_stale_copies(const std::filesystem::path& folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto now = fs::file_time_type::clock::now();
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(kCopyPrefix, 0) != 0) continue;
    struct stat st {};
    if (::lstat(it->path().c_str(), &st) != 0 || !S_ISREG(st.st_mode) || st.st_uid != ::getuid())
      continue;
    std::error_code time_ec;
    const auto written = fs::last_write_time(it->path(), time_ec);
    if (!time_ec && now - written > std::chrono::minutes(10)) fs::remove(it->path(), time_ec);
  }
}

}  // namespace

void ScriptLibrary::load(const std::filesystem::path& library, const HostTable& table,
                         std::int32_t seed) {
  unload();
  const std::filesystem::path folder = std::filesystem::temp_directory_path();
  remove_stale_copies(folder);
  // A private copy: dlopen of the same path would share the script's globals. Removed as soon
  // as it is loaded (the mapping stays), so a crash, a kill or Halt leaves nothing behind.
  std::string tmpl = (folder / (std::string(kCopyPrefix) + "XXXXXX")).string();
  const int fd = ::mkstemp(tmpl.data());
  if (fd < 0) throw std::runtime_error("cannot create a temporary copy of " + library.string());
  ::close(fd);
  std::filesystem::copy_file(library, tmpl, std::filesystem::copy_options::overwrite_existing);
  {
    FpuGuard guard;  // the Pascal RTL's start-up sets its own FPU masks
    handle_ = ::dlopen(tmpl.c_str(), RTLD_NOW | RTLD_LOCAL);
  }
  std::error_code ec;
  std::filesystem::remove(tmpl, ec);
  // dladdr names the copy's path; addr2line reads the same bytes' line table (fpc -g) from
  // the compiled library.
  copy_ = tmpl;
  library_ = library;
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

std::string ScriptLibrary::describe(std::uintptr_t address, bool is_return) const {
  Dl_info info{};
  if (!handle_ || ::dladdr(reinterpret_cast<void*>(address), &info) == 0 || !info.dli_fbase)
    return {};
  if (copy_ != info.dli_fname) return {};  // not the script's code
  char offset[32];
  std::snprintf(
      offset, sizeof offset, "0x%lx",
      static_cast<unsigned long>(address - reinterpret_cast<std::uintptr_t>(info.dli_fbase) -
                                 (is_return ? 1 : 0)));
  std::string quoted = "'";
  for (char c : library_.string())
    quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  const std::string command = "addr2line -f -e " + quoted + "' " + offset + " 2>/dev/null";
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

ScriptLibrary::Outcome ScriptLibrary::run(int which, double now_s, std::string& error) {
  char message[2048] = {0};
  int status = 0;
  {
    FpuGuard guard;
    status = run_(which, now_s, message, static_cast<std::int32_t>(sizeof message));
  }
  if (status == 0) return Outcome::returned;
  error = message;
  return status == 2 ? Outcome::halted : Outcome::raised;
}

}  // namespace s2sim::pascal
