#pragma once
/// \file
/// The kinds of the links plugin, each defined in its own file; plugin.cpp lists them.

#include <s2sim/plugin.hpp>

namespace s2sim::links {

s2sim_kind_entry remote_kind();         ///< remote.cpp: UDP, docs/remote.md
s2sim_kind_entry serial_kind();         ///< serial.cpp: a pseudo-terminal, docs/remote.md
s2sim_kind_entry camera_stream_kind();  ///< camera_stream.cpp: JPEG over UDP, docs/remote.md

}  // namespace s2sim::links
