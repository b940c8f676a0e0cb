#pragma once
/// \file
/// From a SimTwo `control.pas` to a loadable library: the generated wrapper and support unit,
/// Free Pascal (`fpc -Mdelphi`), and a cache keyed by the hash of everything compiled and the
/// compiler's version (docs/scripting.md, "Compilation").

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace s2sim::pascal {

/// Where and with what a script is compiled.
struct CompilerSettings {
  std::string compiler = "fpc";     ///< S2SIM_FPC overrides
  std::filesystem::path cache_dir;  ///< S2SIM_PASCAL_CACHE, else $XDG_CACHE_HOME/s2sim/pascal
  /// From the environment: S2SIM_FPC, S2SIM_PASCAL_CACHE, XDG_CACHE_HOME, HOME.
  static CompilerSettings from_environment();
};

/// One located compiler message.
struct CompileMessage {
  std::string file;
  int line = 0, column = 0;
  std::string text;  ///< "Fatal: Syntax error, ";" expected but "IF" found"
};

struct CompileResult {
  enum class Status { ok, compiler_missing, failed } status = Status::failed;
  std::filesystem::path library;  ///< the cached library (ok)
  std::vector<CompileMessage> errors;
  std::string output;  ///< the compiler's full output (failed, compiler_missing)
};

/// The support unit's text (pascal/s2simtwo.pas with the host function numbers filled in).
std::string support_unit_text();
/// The library wrapper that includes the script by its file name (the generated copy next to
/// it; its text decides whether Initialize must be supplied).
std::string wrapper_text(const std::filesystem::path& script, const std::string& script_text);

/// Compiles `script` unless the cache has it. Never throws for a compile error: the caller
/// decides (a located s2sim::Error for a scene, a message in the viewer).
CompileResult compile_script(const std::filesystem::path& script, const CompilerSettings& settings);

}  // namespace s2sim::pascal
