#pragma once
/// \file
/// Signal-name helpers: the paths of signals and inputs, glob matching (the "did you mean" of
/// an unknown name is common/closest_names.hpp).
///
/// Path index: every signal and input name is built by one of these functions (docs/signals.md
/// lists the names themselves). A scene ID becomes one segment (`segment`); a `scope` is a
/// robot's path or `world` for what belongs to no robot.
///
///   robots/<robot>                          robot_path
///   robots/<robot>/solids/<solid>           solid_path(robot_path(r), solid)
///   things/<thing>                          thing_path
///   <scope>/axes/<axis>                     axis_path(scope, axis)
///   <scope>/joints/<joint>                  joint_path(scope, joint)
///   [robots/<robot>/]<folder>/<component>   component_path(robot_path(r) or "", folder, id)
///   <prefix>/<field>                        field_path(prefix, field), e.g. `.../axes/a/pos`
///   world                                   kWorldScope

#include <string>
#include <string_view>

namespace s2sim::sim {

/// A scene ID as one path segment of a signal name: '/' would split it, so it becomes '_'.
std::string segment(std::string_view id);

/// The scope of scene-level joints and axes.
inline constexpr std::string_view kWorldScope = "world";

/// `robots/<robot>`.
std::string robot_path(std::string_view robot_id);
/// `<robot_path>/solids/<solid>`.
std::string solid_path(std::string_view robot_path, std::string_view solid_id);
/// `things/<thing>`.
std::string thing_path(std::string_view thing_id);
/// `<scope>/axes/<axis>`, scope a robot_path or kWorldScope.
std::string axis_path(std::string_view scope, std::string_view axis_name);
/// `<scope>/joints/<joint>`, scope a robot_path or kWorldScope.
std::string joint_path(std::string_view scope, std::string_view joint_id);
/// `<robot_path>/<folder>/<id>`, or `<folder>/<id>` for a scene-level component (empty
/// robot_path); folder is `sensors`, `controllers`, `actuators`...
std::string component_path(std::string_view robot_path, std::string_view folder,
                           std::string_view id);
/// `<prefix>/<field>`: one value under a path, e.g. `pos` of an axis.
std::string field_path(std::string_view prefix, std::string_view field);

/// Glob match: `*` matches any run of characters (including '/'), `?` exactly one.
bool glob_match(std::string_view pattern, std::string_view text);

/// A double as exact decimal text ("%.17g": it reads back bit for bit through the expression
/// parser), for attributes the kernel writes into a component's element.
std::string exact_decimal(double v);
/// A double in 9 significant digits ("%.9g"), for messages.
std::string short_decimal(double v);

}  // namespace s2sim::sim
