#pragma once
// What the analyses of a gear pair's mesh share in their settings: the mesh force model
// (mesh_force, mesh_harmonics, cyclic_forced_response; pair_model.hpp, tooth_force.hpp).

namespace geardyn::analyses {

/// The mesh force model: the dynamic mesh (the pair's equivalent mass on the time-varying mesh
/// stiffness) or infinite inertias (F_d(t) = F_s k(t) / k_mean, no dynamics).
enum class MeshForceModel { Dynamic, InfiniteInertia };

}  // namespace geardyn::analyses
