// Compilation of a SimTwo script with Free Pascal, and the compile cache. The wrapper includes
// ({$I}) a copy of the user's file that differs only on its routines' begin lines
// (zero_locals.hpp), under the same name: the compiler's messages carry the user's lines.
#include "compiler.hpp"

#include "host_ids.hpp"
#include "zero_locals.hpp"

#include <unistd.h>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

namespace s2sim::pascal {

namespace {

std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// Runs `command` (through the shell, stderr joined); returns its exit status and output.
int run(const std::string& command, std::string& output) {
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0)
    output.append(buf.data(), n);
  const int status = ::pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// FNV-1a, 64 bit, as 16 hex digits: enough to key a cache, not a security hash.
std::string hash_hex(const std::string& data) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : data) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  char out[17];
  std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h));
  return out;
}

/// The compiler's version string, or empty when it cannot be run.
std::string compiler_version(const std::string& compiler) {
  std::string out;
  if (run(shell_quote(compiler) + " -iV", out) != 0) return {};
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r'))
    out.pop_back();
  return out;
}

bool declares_initialize(const std::string& text) {
  static const std::regex re(R"(\bprocedure\s+initialize\s*;)", std::regex::icase);
  return std::regex_search(text, re);
}

}  // namespace

CompilerSettings CompilerSettings::from_environment() {
  CompilerSettings s;
  if (const char* fpc = std::getenv("S2SIM_FPC"); fpc && *fpc) s.compiler = fpc;
  if (const char* dir = std::getenv("S2SIM_PASCAL_CACHE"); dir && *dir) {
    s.cache_dir = dir;
  } else if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    s.cache_dir = std::filesystem::path(xdg) / "s2sim" / "pascal";
  } else if (const char* home = std::getenv("HOME"); home && *home) {
    s.cache_dir = std::filesystem::path(home) / ".cache" / "s2sim" / "pascal";
  } else {
    s.cache_dir = std::filesystem::temp_directory_path() / "s2sim-pascal";
  }
  return s;
}

std::vector<std::pair<std::string, std::string>> support_units() {
  std::string ids = "const\n";
  for (int i = 0; i < static_cast<int>(HostFn::count); ++i)
    ids += "  h" + std::string(kHostFnNames[i]) + " = " + std::to_string(i) + ";\n";
  std::vector<std::pair<std::string, std::string>> units;
  for (int u = 0; u < kSupportUnitCount; ++u) {
    std::string text = kSupportUnits[u].text;
    const std::string mark = "{S2SIM_HOST_IDS}";
    if (const auto at = text.find(mark); at != std::string::npos)
      text.replace(at, mark.size(), ids);
    units.emplace_back(kSupportUnits[u].file, std::move(text));
  }
  return units;
}

std::string wrapper_text(const std::filesystem::path& script, const std::string& script_text) {
  std::string w =
      "library s2script;\n"
      "{$mode delphi}{$H+}\n"
      "uses SysUtils, Classes, Math, Types, Variants, s2simtwo_types, s2simtwo_engine,\n"
      "  s2simtwo_matrix, s2simtwo_helpers, s2simtwo_astar, s2simtwo, s2simtwo_rendering,\n"
      "  s2simtwo_paint, s2simtwo_waypoints;\n"
      "{$I '" +
      script.filename().string() + "'}\n";
  if (!declares_initialize(script_text))  // SimTwo compiles it and fails at the first run
    w += "procedure Initialize;\nbegin\n  raise Exception.Create('Unknown procedure: "
         "Initialize');\nend;\n";
  w += R"PAS(
function s2s_abi: longint; cdecl;
begin
  result := 1;
end;

procedure s2s_bind(table: PHostTable; seed: longint); cdecl;
begin
  Host := table^;
  RandSeed := seed;
end;

{ which: 0 Initialize, 1 Control. 0 = ok; 1 = raised, the message (class, text, where) in err;
  2 = the script called Halt, 'Halt(code)' and where in err. }
function s2s_run(which: longint; now_s: double; err: PChar; errcap: longint): longint; cdecl;
var msg: string;
    frames: PCodePointer;
    i: longint;
begin
  result := 0;
  Time := now_s;
  try
    S2SimTakeUDPData;
    if which = 0 then Initialize else Control;
    S2SimPublishHUD;
  except
    on H: TScriptHalt do begin
      msg := 'Halt(' + IntToStr(H.Code) + ') | $' + HexStr(ExceptAddr);
      frames := ExceptFrames;
      for i := 0 to ExceptFrameCount - 1 do
        msg := msg + ' | $' + HexStr(frames[i]);
      StrPLCopy(err, msg, errcap - 1);
      S2SimPublishHUD;
      result := 2;
    end;
    on E: Exception do begin
      { the raising address, then the callers, as bare addresses: the host names the first
        in the user's file with addr2line. Not the RTL's line-info unit: it walks past the end
        of envp to find the auxiliary vector, which is heap garbage once the host has called
        setenv (a segfault seen in CI). }
      msg := E.ClassName + ': ' + E.Message + ' | $' + HexStr(ExceptAddr);
      frames := ExceptFrames;
      for i := 0 to ExceptFrameCount - 1 do
        msg := msg + ' | $' + HexStr(frames[i]);
      StrPLCopy(err, msg, errcap - 1);
      result := 1;
    end;
  end;
end;

exports s2s_abi, s2s_bind, s2s_run;

begin
end.
)PAS";
  return w;
}

CompileResult compile_script(const std::filesystem::path& script,
                             const CompilerSettings& settings) {
  CompileResult result;
  const std::string version = compiler_version(settings.compiler);
  if (version.empty()) {
    result.status = CompileResult::Status::compiler_missing;
    result.output = "the Free Pascal compiler '" + settings.compiler + "' cannot be run";
    return result;
  }
  // The generated copy the wrapper includes: the user's text with its locals zeroed on the
  // begin lines (zero_locals.hpp), under the user's file name, so messages name it.
  const std::string text = zero_locals(read_file(script));
  const auto units = support_units();
  std::string support;
  for (const auto& [file, unit] : units)
    support += file + '\0' + unit + '\0';
  const std::string wrapper = wrapper_text(script, text);
  const std::string key = hash_hex(text + '\0' + support + '\0' + wrapper + '\0' + version);
  std::error_code ec;
  std::filesystem::create_directories(settings.cache_dir, ec);
  const auto cached = settings.cache_dir / ("script-" + key + ".so");
  result.library = cached;
  if (std::filesystem::exists(cached)) {
    result.status = CompileResult::Status::ok;
    return result;
  }
  // A private build folder; the library is renamed into the cache only when complete, so
  // concurrent processes never see half a file (rename is atomic within a file system).
  std::string tmpl = (settings.cache_dir / ("build-" + key + "-XXXXXX")).string();
  if (!::mkdtemp(tmpl.data())) {
    result.output = "cannot create a build folder in " + settings.cache_dir.string();
    return result;
  }
  const std::filesystem::path build = tmpl;
  {
    for (const auto& [file, unit] : units)
      std::ofstream(build / file, std::ios::binary) << unit;
    std::ofstream(build / "s2script.pas", std::ios::binary) << wrapper;
    std::ofstream(build / script.filename(), std::ios::binary) << text;
  }
  // In the build folder: fpc looks for units in its working folder first, and one of the same
  // name where the user runs S2Sim (a stale s2simtwo.ppu) would be taken for ours.
  // A compiler named by a relative path (S2SIM_FPC=./fpc) is the caller's, not the folder's.
  const std::string compiler = settings.compiler.find('/') != std::string::npos
                                   ? std::filesystem::absolute(settings.compiler).string()
                                   : settings.compiler;
  const std::string command = "cd " + shell_quote(build.string()) + " && " + shell_quote(compiler) +
                              " -Mdelphi -g -O1 -vewn -Fu" + shell_quote(build.string()) + " -FE" +
                              shell_quote(build.string()) + " " +
                              shell_quote((build / "s2script.pas").string());
  const int status = run(command, result.output);
  const auto built = build / "libs2script.so";
  if (status == 0 && std::filesystem::exists(built)) {
    std::filesystem::rename(built, cached, ec);
    if (ec) {
      result.output += "\ncannot move the library into the cache: " + ec.message();
    } else {
      result.status = CompileResult::Status::ok;
    }
  } else {
    // "file(line,col) Error: text"; messages about the generated files are ours.
    static const std::regex re(R"(^(.*)\((\d+),(\d+)\) (Error|Fatal): (.*)$)");
    std::istringstream lines(result.output);
    std::string line;
    while (std::getline(lines, line)) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      std::smatch m;
      if (!std::regex_match(line, m, re)) continue;
      CompileMessage msg;
      const std::string file = std::filesystem::path(m[1].str()).filename().string();
      msg.file = file == script.filename().string() ? script.string() : file;
      msg.line = std::stoi(m[2]);
      msg.column = std::stoi(m[3]);
      msg.text = m[4].str() + ": " + m[5].str();
      result.errors.push_back(std::move(msg));
    }
  }
  std::filesystem::remove_all(build, ec);
  return result;
}

}  // namespace s2sim::pascal
