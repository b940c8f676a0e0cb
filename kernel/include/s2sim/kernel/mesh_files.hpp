#pragma once
/// \file
/// How S2Sim reads a mesh file, wherever it reads one: collision hulls of imported robots,
/// painting targets, the renderer (docs/models/import.md, "Meshes").

namespace Assimp {
class Importer;
}

namespace s2sim {

/// Prepares an assimp importer the way every mesh file is read. A COLLADA file's `<unit>` is
/// applied (its coordinates come out in metres); its `<up_axis>` is not: the file's axes are
/// the link's axes, as ROS and Gazebo draw them, where assimp by default would turn a `Z_UP`
/// file into its own Y-up convention.
void configure_mesh_importer(Assimp::Importer& importer);

}  // namespace s2sim
