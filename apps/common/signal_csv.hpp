#pragma once
/// \file
/// The signal CSV format of S2Sim: which signals a list of `--signals` patterns selects, the
/// header line `time [s],name [unit],...` and the rows (`%.6f` time, `%.10g` values). The
/// runner's `--log` and the viewer's chart export both write through here, so their files are
/// identical for the same run.

#include <s2sim/kernel/simulation.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

namespace s2sim::apps {

/// The signals the patterns select, in pattern order, each at most once and never `time`
/// (always the first column). No pattern selects every signal. Throws s2sim::Error (usage)
/// for a pattern that matches nothing, with "did you mean" for a plain name. `option` names
/// the option in the message (e.g. "--signals").
std::vector<std::size_t> select_signals(const Simulation& sim,
                                        const std::vector<std::string>& patterns,
                                        const std::string& option = "--signals");

/// One CSV field per RFC 4180: as it is, or quoted (inner quotes doubled) when it holds a
/// comma, a quote or a line break.
std::string csv_field(const std::string& text);

/// Writes the header line of the selected signals (fields quoted per RFC 4180 where needed).
void write_csv_header(std::FILE* out, const Simulation& sim, std::span<const std::size_t> signals);

/// The index of the first value that is not finite, -1 when all are: such a value never
/// reaches a file (the writers stop with an error naming the signal).
std::ptrdiff_t first_non_finite(std::span<const double> values);

/// Writes one row; no allocation.
void write_csv_row(std::FILE* out, double time_s, std::span<const double> values);

}  // namespace s2sim::apps
