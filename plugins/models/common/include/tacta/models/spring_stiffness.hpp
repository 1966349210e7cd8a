// Spring constants of the mesh edges from the material's E and nu (N/m, one per mesh edge), for
// mass_spring's springs and bullet_softbody's links. Two rules (docs/VALIDATION.md measures both):
//
// van_gelder (default): k_e = E sum_T V(T) / L_e^2 over the tets T around edge e (A. Van Gelder,
// "Approximate simulation of elastic membranes by triangulated spring meshes", J. Graphics Tools
// 3(2), 1998, gives k = E t sum area / L^2 for triangles; this is its volume form). An
// isotropic network of such springs has Young's modulus E and, like every central-force
// network, Poisson's ratio 1/4 whatever nu says (Cauchy relations).
// fem_projection: each tet's linear-FEM stiffness block of the edge's ends a, b,
// K_ab = V [lambda g_a g_b^T + mu g_b g_a^T + mu (g_a . g_b) I] (g: shape-function gradients),
// projected on a spring's block -k n n^T (n the unit edge) in the Frobenius norm:
// k = -n^T K_ab n = V [(lambda + mu) / L^2 - mu g_a . g_b], summed over the tets. Element
// stiffness matching in the spirit of Lloyd, Szekely and Harders (IEEE TVCG 13(5), 2007); it
// carries lambda into every spring, so at nu 0.45 the network is some 3.6x stiffer than E in
// tension. An edge whose sum is negative (very obtuse dihedral angles) gets no stiffness.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tacta/model_api.h"

namespace tacta::models {

enum class StiffnessRule { kVanGelder = 0, kFemProjection = 1 };  // scene choice order

// Throws std::invalid_argument starting with `model` and naming the tet or edge when the mesh
// is not usable (a node out of range, a degenerate tet, a tet edge missing from mesh.edges, a
// zero-length edge).
std::vector<double> edge_stiffness(const char* model, const tacta_mesh_view& mesh,
                                   const tacta_material& material, StiffnessRule rule);

// "van_gelder" or "fem_projection", as the scene names the rule.
const char* stiffness_rule_name(StiffnessRule rule);
// "median M (min A, max B)" of the values, 3 significant digits, for a model's describe().
std::string median_and_range(std::vector<double> values);

}  // namespace tacta::models
