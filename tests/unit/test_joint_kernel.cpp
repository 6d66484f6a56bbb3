// The optimised joint kernel (precomputed quadrature, forces gathered per node in parallel)
// against the plain serial oracle: the same nodal forces, point states, joint statuses and
// failure order, bit for bit, on 1 and 2 threads, through a loading that softens and breaks
// joints. Meshes are big enough (~6e3 joints, ~1.3e4 gathered nodes) for both parallel loops
// to run on several threads.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "joint/joint_forces.hpp"
#include "support/box_mesh.hpp"
#include "support/model_builder.hpp"

using namespace dspdem;
using namespace dspdem::testsupport;

namespace {
// The same to the bit, except the work integrals and the shear work at a break: the oracle
// keeps every point in full and sums the work by the trapezoid rule from the first step; the
// kernel keeps elastic points lean and starts that sum from the closed form 1/2 s d when a
// point leaves the elastic branch (lean_point.hpp). For a linear spring both are exact, so
// they may differ by rounding only, which is relative to the largest work a point saw on its
// path (a joint squeezed and let go again ends near zero): 1e-12 of k_n amp^2, the scale of
// the largest work densities this loading produces, some thousand ulps of it.
bool close_work(Real a, Real b, Real floor) {
  return std::abs(a - b) <= 1e-12 * std::max({std::abs(a), std::abs(b), floor});
}
// Field by field, each to the bit: not one memcmp of the whole struct, whose padding after
// `status` holds whatever the compiler left there (clang's copies differ there, GCC's did not).
// The last slip's components (su, sv) only where the point is kept in full: a lean point does
// not keep them (its law needs the magnitude alone; the first update in full sets them), and
// the oracle keeps every point in full.
bool same_state(const joint::CohesiveState& a, const joint::CohesiveState& b, Real work_floor, bool full) {
  using S = joint::CohesiveState;
  // 17 Reals and status, then padding: a new field changes the size or takes the padding.
  static_assert(sizeof(S) == 18 * sizeof(Real) && offsetof(S, status) + sizeof(S::status) + 4 == sizeof(S),
                "CohesiveState has a new field: compare it here");
  for (Real S::*f : {&S::dn_max, &S::ds_plastic, &S::ks_secant, &S::damage, &S::friction, &S::dn, &S::ds, &S::sn,
                     &S::ss, &S::ss_forced, &S::fu, &S::fv})
    if (std::bit_cast<std::uint64_t>(a.*f) != std::bit_cast<std::uint64_t>(b.*f)) return false;
  if (full)
    for (Real S::*f : {&S::su, &S::sv})
      if (std::bit_cast<std::uint64_t>(a.*f) != std::bit_cast<std::uint64_t>(b.*f)) return false;
  return a.status == b.status && close_work(a.work_n, b.work_n, work_floor) &&
         close_work(a.work_s, b.work_s, work_floor) && close_work(a.diss_II_at_break, b.diss_II_at_break, work_floor);
}

enum class Law { Paper, Coupled, ModeI, Residual };

void compare_kernels(CellType type, joint::Quadrature rule, int threads, Law law = Law::Paper, bool offsets = false) {
  CaseConfig c = simple_case(30e9, 0.2, 2400);
  // Mode I fails in opening only: 3 % of the fracture energy (w_GI 2 um), so that the
  // loading below breaks joints under it too.
  // paper_residual breaks once the cohesion is spent along the plastic slip, 2 G_fII / c:
  // G_fII 3 N/m (0.6 um) for the same reason.
  make_fracturable(c, 3e6, law == Law::ModeI ? 3 : 100, 10e6, 30, law == Law::Residual ? 3 : 1000);
  for (auto& jm : c.joint_materials)
    jm.coupled = law == Law::Coupled, jm.mode_i = law == Law::ModeI, jm.residual = law == Law::Residual;
  const int n = type == CellType::Tet4 ? 8 : 14;
  const Model m = build_model(c, box_mesh(type, n, n, n, Vec3(0.1, 0.1, 0.1), 0.2));
  ASSERT_GT(m.joints.size(), 4000);
  joint::JointSet ref = m.joints, opt = m.joints;
  for (auto* js : {&ref, &opt}) js->quadrature.assign(js->params.size(), rule);
  // Extrinsic joints' offsets (an opening and a slip on the face's frame per point, as
  // open_face leaves them), of the loading's size below: both kernels add them.
  if (offsets)
    for (auto* js : {&ref, &opt}) {
      js->offset.assign(16 * static_cast<std::size_t>(js->size()), 0.0);
      for (std::size_t i = 0; i < js->offset.size(); ++i)
        if (i % 4 != 3) js->offset[i] = 2e-6 * std::sin(0.61 * static_cast<double>(i));
    }
  // Some joints released (contact took over): the kernel takes joints in batches of equal
  // ones and the rest one by one, so both paths run.
  for (auto* js : {&ref, &opt})
    for (Index j = 5; j < js->size(); j += 97) js->released[j] = 1;
  omp_set_num_threads(threads);
  std::vector<Real> slots;
  const std::size_t nd = m.fem.x0.size();
  // Node displacements growing to 5 um as the 4th power of the step, a different phase at
  // every dof: the first steps stay elastic (whole batches of lean points: the kernel's
  // vector path), then some points leave the elastic branch among lean ones, and over the
  // steps the joints go through softening to failure (between 10 % and all of them, checked
  // below), and some close again in compression.
  const Real amp = 5e-6;
  const Real work_floor = m.joints.params.front().kn * amp * amp;
  Index broken = 0;
  bool lean_and_full = false;
  for (int step = 1; step <= 30; ++step) {
    // Half way, more joints are released, a whole batch of 4 among them: the kernel's gather
    // (active joints only) must be rebuilt and the all-inactive batch skipped.
    if (step == 15)
      for (auto* js : {&ref, &opt}) {
        for (Index j = 3; j < js->size(); j += 13) js->released[j] = 1;
        for (Index j = 400; j < 404; ++j) js->released[j] = 1;
      }
    std::vector<Real> x(nd), f_ref(nd), f_opt(nd);
    for (std::size_t i = 0; i < nd; ++i) {
      x[i] = m.fem.x0[i] + amp * std::pow(step / 30.0, 4) * std::sin(0.37 * static_cast<double>(i) + 0.1 * step);
      f_ref[i] = f_opt[i] = std::cos(0.21 * static_cast<double>(i));  // element forces stand-in
    }
    joint::add_joint_forces_reference(ref, x.data(), f_ref.data());
    joint::add_joint_forces(opt, x.data(), f_opt.data(), slots);
    for (std::size_t i = 0; i < nd; ++i) ASSERT_EQ(f_ref[i], f_opt[i]) << "dof " << i << " at step " << step;
    ASSERT_EQ(ref.failed, opt.failed) << "step " << step;
    Index lean = 0, full = 0;
    for (Index j = 0; j < opt.size(); ++j)
      for (int g = 0; g < opt.npf[j]; ++g) (opt.full[4 * j + g] ? full : lean) += 1;
    lean_and_full = lean_and_full || (lean > 0 && full > 0);
    for (Index j = 0; j < ref.size(); ++j) {
      ASSERT_EQ(ref.status[j], opt.status[j]) << "joint " << j << " at step " << step;
      for (int g = 0; g < 4; ++g)
        ASSERT_TRUE(same_state(ref.point_state(4 * j + g), opt.point_state(4 * j + g), work_floor, opt.full[4 * j + g]))
            << "joint " << j << " point " << g << " at step " << step;
    }
  }
  for (Index j = 0; j < ref.size(); ++j) broken += ref.status[j] == joint::JointStatus::Broken;
  // The loading must have exercised failure, and some points must have stayed lean, or the
  // comparison proves little.
  EXPECT_GT(broken, ref.size() / 10);
  EXPECT_LT(broken, ref.size());
  EXPECT_TRUE(lean_and_full) << "no step had lean and full points side by side";
}
}  // namespace

TEST(JointKernel, TetGaussMatchesTheSerialOracleOnOneThread) {
  compare_kernels(CellType::Tet4, joint::Quadrature::Gauss, 1);
}
TEST(JointKernel, TetGaussMatchesTheSerialOracleOnTwoThreads) {
  compare_kernels(CellType::Tet4, joint::Quadrature::Gauss, 2);
}
TEST(JointKernel, TetNodalMatchesTheSerialOracleOnTwoThreads) {
  compare_kernels(CellType::Tet4, joint::Quadrature::Nodal, 2);
}
// The text's shear softening (paper_residual): the paper's elastic gate, its own law and its
// own forced break (a failed face keeps its friction).
TEST(JointKernel, TetGaussPaperResidualMatchesTheSerialOracleOnTwoThreads) {
  compare_kernels(CellType::Tet4, joint::Quadrature::Gauss, 2, Law::Residual);
}
// The disc's combination: nodal points (the kernel's own branch, which skips the zero shape
// values) under the coupled law (its own elastic gate in lean_update).
TEST(JointKernel, TetNodalCoupledMatchesTheSerialOracleOnTwoThreads) {
  compare_kernels(CellType::Tet4, joint::Quadrature::Nodal, 2, Law::Coupled);
}
TEST(JointKernel, HexNodalMatchesTheSerialOracleOnOneThread) {
  compare_kernels(CellType::Hex8, joint::Quadrature::Nodal, 1);
}
TEST(JointKernel, HexGaussMatchesTheSerialOracleOnTwoThreads) {
  compare_kernels(CellType::Hex8, joint::Quadrature::Gauss, 2);
}
// The impact beam's combination: quadrilaterals with Gauss points under the mode I law (no
// shear limit in lean_update).
TEST(JointKernel, HexGaussModeIMatchesTheSerialOracleOnTwoThreads) {
  compare_kernels(CellType::Hex8, joint::Quadrature::Gauss, 2, Law::ModeI);
}
// Extrinsic joints: the offsets added on the face's frame, by both kernels alike.
TEST(JointKernel, TetGaussWithExtrinsicOffsetsMatchesTheSerialOracleOnTwoThreads) {
  compare_kernels(CellType::Tet4, joint::Quadrature::Gauss, 2, Law::Paper, true);
}
TEST(JointKernel, HexNodalWithExtrinsicOffsetsMatchesTheSerialOracleOnTwoThreads) {
  compare_kernels(CellType::Hex8, joint::Quadrature::Nodal, 2, Law::Paper, true);
}
