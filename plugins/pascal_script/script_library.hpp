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
  /// Runs Initialize (which 0) or Control (1); false with `error` set when it raised.
  bool run(int which, double now_s, std::string& error);
  /// "ROUTINE at file:line" for a code address inside the library, from its debug line table
  /// (binutils' addr2line, which fpc itself needs); empty when unknown.
  std::string describe(std::uintptr_t address) const;

 private:
  void* handle_ = nullptr;
  std::filesystem::path copy_;  // the private copy, removed at unload
  int (*run_)(std::int32_t, double, char*, std::int32_t) = nullptr;
  HostTable table_{};
};

}  // namespace s2sim::pascal
