#include "sim/remesh/remesh.h"

#include <stdexcept>
#include <string>

#include "base/timer.h"
#include "sim/remesh/curvature.h"
#include "sim/remesh/point_locator.h"

namespace weft::sim::remesh {

SecondDerivatives patch_second_derivatives(const std::vector<VertexPatch>& patches) {
  SecondDerivatives second = SecondDerivatives::Zero(static_cast<Eigen::Index>(patches.size()), 9);
  for (size_t v = 0; v < patches.size(); ++v)
    if (const VertexPatch& p = patches[v]; p.valid)
      second.row(static_cast<Eigen::Index>(v)) << p.x_uu.transpose(), p.x_uv.transpose(),
          p.x_vv.transpose();
  return second;
}

RemeshOutput remesh(const RemeshInput& input, const RemeshParams& params) {
  check_size_field_params(params.size);
  const auto rows = input.material.rows();
  if (input.positions.rows() != rows || input.velocities.rows() != rows)
    throw std::invalid_argument("remesh input: " + std::to_string(input.positions.rows()) +
                                " positions and " + std::to_string(input.velocities.rows()) +
                                " velocities for " + std::to_string(rows) +
                                " vertices, expected one of each per vertex");
  RemeshOutput out;
  base::Stopwatch phase;
  const std::vector<VertexPatch> patches =
      vertex_patches(input.material, input.triangles, input.positions);
  out.old_curvature = patch_curvatures(patches);
  out.old_target_size = target_sizes(out.old_curvature, params.size);

  // The size field between the old vertices: barycentric interpolation, as the kinematics.
  const PointLocator old_mesh(input.material, input.triangles);
  const Eigen::VectorXd& h = out.old_target_size;
  const Triangles& tri = input.triangles;
  const SizeFunction size = [&](const Vec2& p) {
    const Location at = old_mesh.locate(p);
    return at.barycentric[0] * h(tri(at.triangle, 0)) + at.barycentric[1] * h(tri(at.triangle, 1)) +
           at.barycentric[2] * h(tri(at.triangle, 2));
  };
  out.curvature_s = phase.seconds();
  phase.restart();
  out.mesh = mesh_domain(input.material, input.triangles, input.pins, size, params.mesher);
  out.mesher_s = phase.seconds();
  phase.restart();
  out.transfer = make_transfer_map(old_mesh, out.mesh.material, out.mesh.new_to_old);
  if (params.positions == PositionTransfer::quadratic) {
    out.positions = transfer_quadratic(out.transfer, input.material, input.triangles,
                                       input.positions, patch_second_derivatives(patches));
  } else {
    out.positions = transfer(out.transfer, input.triangles, input.positions);
  }
  out.velocities = transfer(out.transfer, input.triangles, input.velocities);
  out.transfer_s = phase.seconds();
  return out;
}

}  // namespace weft::sim::remesh
