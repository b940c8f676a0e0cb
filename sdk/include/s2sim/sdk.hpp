#pragma once
/// \file
/// Everything a plugin needs: `#include <s2sim/sdk.hpp>`.

#include <s2sim/component.hpp>
#include <s2sim/error.hpp>
#include <s2sim/image.hpp>
#include <s2sim/math.hpp>
#include <s2sim/params.hpp>
#include <s2sim/plugin.hpp>
#include <s2sim/random.hpp>
#include <s2sim/schedule.hpp>
#include <s2sim/sensor.hpp>
#include <s2sim/span.hpp>
#include <s2sim/version.hpp>
