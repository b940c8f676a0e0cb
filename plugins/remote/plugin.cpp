/// \file
/// The links plugin: kinds that connect a simulation to programs outside it.

#include "kinds.hpp"

S2SIM_PLUGIN("links", s2sim::links::remote_kind(), s2sim::links::serial_kind(),
             s2sim::links::camera_stream_kind());
