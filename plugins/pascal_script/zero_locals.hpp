#pragma once
/// \file
/// Pascal Script zero-fills every local variable and every function `Result`; Free Pascal does
/// not (simtwo-script-api.md §6.2 H). `zero_locals` returns a copy of a script in which each
/// routine's `begin` line also sets its locals and its Result to `Default(T)` (or zero bytes for
/// a static array of plain values), inserted after `begin` on the same line so that every line
/// number stays the user's. What it does not understand (a nested routine, an inline record)
/// it leaves as written.

#include <string>

namespace s2sim::pascal {

std::string zero_locals(const std::string& script);

}  // namespace s2sim::pascal
