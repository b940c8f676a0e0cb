#pragma once
/// \file
/// The drive train's defaults: the one place they live (the loader hands the elements over as
/// written). Documented in docs/models/dc-motor.md, "Parameters"; SimTwo's values
/// (simtwo-format.md §4.10) unless said otherwise.

#include <cstdint>

namespace s2sim::drive_train::defaults {

// <motor>
inline constexpr double kMotorRi = 1;       ///< Ω
inline constexpr double kMotorLi = 0;       ///< H
inline constexpr double kMotorKi = 1.4e-2;  ///< N·m/A, also V·s/rad
inline constexpr double kMotorVmax = 24;    ///< V
inline constexpr double kMotorImax = 4;     ///< A
inline constexpr bool kMotorActive = true;
inline constexpr bool kMotorSimple = false;
inline constexpr const char* kMotorBackEmf = "physical";  ///< S2Sim: or `simtwo`
/// A per physics step (S2Sim's `slew`; 0 = none): SimTwo's limit under SimTwo semantics.
inline constexpr double kMotorSlewSimTwo = 0.5, kMotorSlewS2Sim = 0;
// <gear>
inline constexpr double kGearRatio = 10;
inline constexpr double kGearKe = 0.05, kGearBe = 0.01, kGearKe2 = 0, kGearKv2 = 0;  ///< unused
// <rotor>
inline constexpr double kRotorJ = 0;      ///< kg·m², reflected as N²·J
inline constexpr double kRotorBv = 1e-3;  ///< parsed, not applied (as SimTwo)
inline constexpr double kRotorFc = 0;     ///< parsed, not applied (as SimTwo)
// <friction>, at the joint
inline constexpr double kFrictionBv = 1e-5;  ///< N·m·s/rad or N·s/m
inline constexpr double kFrictionFc = 1e-3;  ///< N·m or N
// <spring>
inline constexpr double kSpringK = 0;        ///< N·m/rad or N/m
inline constexpr double kSpringZeroPos = 0;  ///< degrees (rotational) or m (slider)
// <encoder>
inline constexpr double kEncoderPpr = 1000;  ///< rounded to a whole count, as SimTwo
inline constexpr double kEncoderMean = 0, kEncoderStdev = -1;  ///< ticks
// encoder period: the scene's control period (SimTwo samples on the script tick)
// <controller>
inline constexpr const char* kControllerMode = "pidspeed";     ///< also when `mode` is absent
inline constexpr double kControllerKp = 1, kControllerKf = 0;  ///< joints
inline constexpr double kWheelControllerKp = 0.5, kWheelControllerKf = 0.5;  ///< `<wheels>`
inline constexpr double kControllerKi = 0, kControllerKd = 0;
/// ms. SimTwo's articulation default is 10 s (quirk 7a); a 10 s controller tick is never what
/// a scene means, so S2Sim uses 10 ms for joints as for wheels.
inline constexpr double kControllerPeriodMs = 10;
inline constexpr bool kControllerActive = false;
/// S2Sim's `law`: `textbook` under S2Sim semantics, `simtwo` under SimTwo's.
inline constexpr const char* kControllerLaw = "textbook";
inline constexpr const char* kControllerLawSimTwo = "simtwo";

}  // namespace s2sim::drive_train::defaults
