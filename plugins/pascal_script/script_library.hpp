#pragma once
/// \file
/// A compiled script loaded into the process: a private copy of the cached library (so that
/// two simulations, or a reset, get fresh script globals), its host table bound, and calls
/// made with every floating-point exception masked, as SimTwo does, the caller's FPU state
/// restored afterwards. Pascal exceptions never cross the boundary: the library's entry
/// catches them and returns the message.

#include <cstdint>
#include <filesystem>
#include <string>

namespace s2sim::pascal {

/// The table the support unit's `THostTable` mirrors (pascal/s2simtwo.pas).
struct HostTable {
  void* host = nullptr;
  double (*call)(void* host, std::int32_t fn, const double* args, std::int32_t nargs,
                 const char* text, std::int32_t text_len, const char* text2,
                 std::int32_t text2_len) = nullptr;
  /// kind 0: text result; 1: numbers result; 2: pending error. Returns the length.
  std::int32_t (*result)(void* host, std::int32_t kind, const void** data) = nullptr;
};

class ScriptLibrary {
 public:
  ScriptLibrary() = default;
  ScriptLibrary(const ScriptLibrary&) = delete;
  ScriptLibrary& operator=(const ScriptLibrary&) = delete;
  ~ScriptLibrary();

  /// Loads a fresh copy of `library` and binds `table`; throws std::runtime_error.
  void load(const std::filesystem::path& library, const HostTable& table, std::int32_t seed);
  void unload();
  bool loaded() const { return handle_ != nullptr; }
  /// How a call into the script ended.
  enum class Outcome { returned, raised, halted };
  /// Runs Initialize (which 0) or Control (1). Raised: `error` holds "class: text | $address
  /// ...". Halted (the script called Halt): `error` holds "Halt(code) | $address ...".
  Outcome run(int which, double now_s, std::string& error);
  /// "ROUTINE at file:line" for a code address inside the library, from its debug line table
  /// (binutils' addr2line, which fpc itself needs); empty when unknown. A return address
  /// (`is_return`) is looked up one byte back, inside its call; a raise's own address as it is.
  std::string describe(std::uintptr_t address, bool is_return) const;

 private:
  void* handle_ = nullptr;
  std::filesystem::path library_;  // the compiled library (the cache's), for its line table
  std::string copy_;  // the private copy's path, as the loader names it; removed once loaded
  int (*run_)(std::int32_t, double, char*, std::int32_t) = nullptr;
  HostTable table_{};
};

}  // namespace s2sim::pascal
