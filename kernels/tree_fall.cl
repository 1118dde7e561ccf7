/* A failed tree's fall on an output frame (docs/damage.md, "What follows a failure"; the CPU reference is
 * trees/TreeFall.hpp fall_displacements): after the modal deformation (a failed tree's modes are at rest),
 * every node above the pivot node (its descendants in the skeleton: the broken top, or for an overturned
 * tree every node but the root) turns about the horizontal axis a = z x d through the pivot, d the
 * direction it falls toward, by the fall's angle, and comes down by its drop; the other nodes (the stump)
 * stay at rest.
 *
 * Work mapping: one falling tree per loop iteration (FW_FLAT_FOR over the falls), its nodes in order.
 * tour: per species (from 2 FwSpecies.skeleton_offset) each node's preorder index and the index past its
 * subtree, so that node k descends from node b when tour_b <= tour_k < end_b. rest_nodes: per species (from
 * 3 FwSpecies.skeleton_offset) each node's rest position, skeleton frame, m. */
#include "common.cl"

__kernel void tree_fall(const int fall_count, __global const FwFall* falls,
                        __global const FwTreeInstance* instances, __global const FwSpecies* species,
                        __global const int* tour, __global const float* rest_nodes,
                        __global float* displacements) {
  FW_FLAT_FOR(f, fall_count) {
    const FwFall fall = falls[f];
    const FwTreeInstance tree = instances[fall.instance];
    const FwSpecies sp = species[tree.species];
    __global const int* nodes_tour = tour + 2 * sp.skeleton_offset;
    __global const float* rest = rest_nodes + 3 * sp.skeleton_offset;
    const int first = nodes_tour[2 * fall.pivot], past = nodes_tour[2 * fall.pivot + 1];
    /* The axis a = z x d, and the pivot in the world. */
    const float ax = -fall.direction[1], ay = fall.direction[0];
    const float cs = tree.cos_yaw, sn = tree.sin_yaw, s = tree.scale;
    __global const float* p = rest + 3 * fall.pivot;
    const float px = s * (cs * p[0] - sn * p[1]), py = s * (sn * p[0] + cs * p[1]), pz = s * p[2];
    for (int n = 0; n < sp.node_count; ++n) {
      __global float* out = displacements + 3 * (tree.node_offset + n);
      const int order = nodes_tour[2 * n];
      if (order <= first || order >= past) { /* the pivot itself and what is not above it */
        out[0] = out[1] = out[2] = 0.0f;
        continue;
      }
      __global const float* r = rest + 3 * n;
      const float vx = s * (cs * r[0] - sn * r[1]) - px, vy = s * (sn * r[0] + cs * r[1]) - py,
                  vz = s * r[2] - pz;
      /* Rodrigues about the horizontal unit axis (ax, ay, 0): v cos + (a x v) sin + a (a . v)(1 - cos). */
      const float along = (ax * vx + ay * vy) * (1.0f - fall.cos_angle);
      const float tx = vx * fall.cos_angle + (ay * vz) * fall.sin_angle + ax * along;
      const float ty = vy * fall.cos_angle + (-ax * vz) * fall.sin_angle + ay * along;
      const float tz = vz * fall.cos_angle + (ax * vy - ay * vx) * fall.sin_angle;
      out[0] = tx - vx;
      out[1] = ty - vy;
      out[2] = tz - vz - fall.drop;
    }
  }
}
