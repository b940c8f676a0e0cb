#pragma once
/// \file
/// The periods a scene's components run at when the scene gives none, shared by the kernel
/// (which schedules the components it attaches) and the plugins (which fall back on them).

namespace s2sim {

/// The period of high-level controllers (a script, a remote link), seconds: SimTwo's 40 ms.
inline constexpr double kDefaultControlPeriod_s = 0.04;

}  // namespace s2sim
