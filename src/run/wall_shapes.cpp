#include "run/wall_shapes.hpp"

#include <vtkAppendPolyData.h>
#include <vtkCellArray.h>
#include <vtkCubeSource.h>
#include <vtkCylinderSource.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSphereSource.h>

#include <cmath>

namespace dspdem {

namespace {
using Quat = Eigen::Quaternion<Real>;

// Copies `pd` with every point moved from the wall's body frame to the world.
vtkSmartPointer<vtkPolyData> placed(vtkPolyData* pd, const Vec3& centre, const Quat& q) {
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(pd);
  vtkPoints* p = out->GetPoints();
  for (vtkIdType i = 0; i < p->GetNumberOfPoints(); ++i) {
    double x[3];
    p->GetPoint(i, x);
    const Vec3 w = centre + q * Vec3(x[0], x[1], x[2]);
    p->SetPoint(i, w(0), w(1), w(2));
  }
  out->GetPointData()->Initialize();  // source normals would be in the body frame
  return out;
}

// A grid of quads over (u, v) in [u0, u1] x [v0, v1] mapped by f(u, v) -> world point.
template <class F>
vtkSmartPointer<vtkPolyData> patch(int nu, int nv, double u0, double u1, double v0, double v1, F f) {
  vtkNew<vtkPoints> pts;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      const Vec3 x = f(u0 + (u1 - u0) * i / nu, v0 + (v1 - v0) * j / nv);
      pts->InsertNextPoint(x(0), x(1), x(2));
    }
  vtkNew<vtkCellArray> quads;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const vtkIdType a = j * (nu + 1) + i, ids[4] = {a, a + 1, a + nu + 2, a + nu + 1};
      quads->InsertNextCell(4, ids);
    }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(pts);
  pd->SetPolys(quads);
  return pd;
}

// Two unit vectors completing `n` to an orthonormal frame.
std::pair<Vec3, Vec3> across(const Vec3& n) {
  const Vec3 t = std::abs(n(0)) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = n.cross(t).normalized();
  return {u, n.cross(u)};
}
}  // namespace

vtkSmartPointer<vtkPolyData> wall_surfaces(const std::vector<WallConfig>& walls, vtkDataSet* frame,
                                           const double bounds[6]) {
  vtkDataArray* pose = frame ? frame->GetFieldData()->GetArray("wall_pose") : nullptr;
  if (walls.empty() || !pose || pose->GetNumberOfComponents() != 7 ||
      pose->GetNumberOfTuples() != static_cast<vtkIdType>(walls.size()))
    return nullptr;
  const Vec3 lo(bounds[0], bounds[2], bounds[4]), hi(bounds[1], bounds[3], bounds[5]);
  const Vec3 mid = 0.5 * (lo + hi);
  const double diag = (hi - lo).norm();
  vtkNew<vtkAppendPolyData> all;
  for (std::size_t k = 0; k < walls.size(); ++k) {
    double p[7];
    pose->GetTuple(static_cast<vtkIdType>(k), p);
    const Vec3 c(p[0], p[1], p[2]);
    const Quat q(p[3], p[4], p[5], p[6]);
    const contact::Wall& w = walls[k].wall;
    switch (w.type) {
      case contact::Wall::Type::Box: {
        vtkNew<vtkCubeSource> box;
        box->SetXLength(2 * w.half(0)), box->SetYLength(2 * w.half(1)), box->SetZLength(2 * w.half(2));
        box->Update();
        all->AddInputData(placed(box->GetOutput(), c, q));
        break;
      }
      case contact::Wall::Type::Cylinder: {
        // vtkCylinderSource stands on y: turn y onto the wall's axis.
        const Quat to_axis = q * Quat::FromTwoVectors(Vec3::UnitY(), w.axis0.normalized());
        vtkNew<vtkCylinderSource> cyl;
        cyl->SetRadius(w.radius), cyl->SetHeight(2 * w.half_length), cyl->SetResolution(48), cyl->CappingOff();
        cyl->Update();
        all->AddInputData(placed(cyl->GetOutput(), c, to_axis));
        for (double end : {-1.0, 1.0}) {
          vtkNew<vtkSphereSource> cap;
          cap->SetRadius(w.radius), cap->SetThetaResolution(32), cap->SetPhiResolution(16);
          cap->SetCenter(0, end * w.half_length, 0);
          cap->Update();
          all->AddInputData(placed(cap->GetOutput(), c, to_axis));
        }
        break;
      }
      case contact::Wall::Type::Jaw: {
        // The arc within the half angle of the jaw's normal, over the framed length of its axis.
        const Vec3 a = (q * w.axis0).normalized(), n = (q * w.normal0).normalized(), b = a.cross(n);
        double z0 = 1e300, z1 = -1e300;
        for (int m = 0; m < 8; ++m) {
          const Vec3 corner((m & 1) ? hi(0) : lo(0), (m & 2) ? hi(1) : lo(1), (m & 4) ? hi(2) : lo(2));
          const double z = (corner - c).dot(a);
          z0 = std::min(z0, z), z1 = std::max(z1, z);
        }
        const double half = std::acos(std::clamp<double>(w.cos_half_angle, -1, 1));
        all->AddInputData(patch(32, 2, -half, half, z0, z1, [&](double t, double z) {
          return Vec3(c + w.radius * (std::cos(t) * n + std::sin(t) * b) + z * a);
        }));
        break;
      }
      case contact::Wall::Type::Plane: {
        // A square on the plane about the foot of the framing centre, as wide as the framing.
        const Vec3 n = (q * w.normal0).normalized();
        const Vec3 foot = mid - (mid - c).dot(n) * n;
        const auto [u, v] = across(n);
        all->AddInputData(patch(1, 1, -0.6 * diag, 0.6 * diag, -0.6 * diag, 0.6 * diag,
                                [&](double s, double t) { return Vec3(foot + s * u + t * v); }));
        break;
      }
    }
  }
  all->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(all->GetOutput());
  return out;
}

}  // namespace dspdem
