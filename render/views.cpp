#include "render/views.hpp"

#include <vtkActor.h>
#include <vtkActor2D.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkDoubleArray.h>
#include <vtkFeatureEdges.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPlane.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataMapper2D.h>
#include <vtkProperty.h>
#include <vtkProperty2D.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkStaticPointLocator.h>
#include <vtkTableBasedClipDataSet.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/error.hpp"
#include "render/colormap.hpp"
#include "render/envelope.hpp"
#include "render/offscreen.hpp"

namespace dspdem::render {

const std::vector<std::string>& stress_fields() {
  static const std::vector<std::string> f = {"von_mises", "max_principal", "sigma_xx", "sigma_yy",    "sigma_zz",
                                             "sigma_xy",  "sigma_yz",      "sigma_xz", "displacement"};
  return f;
}

std::vector<double> field_values(vtkUnstructuredGrid* g, const std::string& field, const std::string& file) {
  const vtkIdType n = g->GetNumberOfCells();
  std::vector<double> out(static_cast<std::size_t>(n));
  auto need = [&](vtkDataArray* a, const char* name) {
    if (!a)
      fail("frame '{}' has no '{}' array (needed for field '{}'); write it with [output] fields", file, name, field);
    return a;
  };
  const char* comps[] = {"sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_yz", "sigma_xz"};
  for (int c = 0; c < 6; ++c)
    if (field == comps[c]) {
      vtkDataArray* s = need(g->GetCellData()->GetArray("stress"), "stress");
      for (vtkIdType e = 0; e < n; ++e) out[e] = s->GetComponent(e, c);
      return out;
    }
  if (field == "von_mises" || field == "max_principal") {
    vtkDataArray* a = need(g->GetCellData()->GetArray(field.c_str()), field.c_str());
    for (vtkIdType e = 0; e < n; ++e) out[e] = a->GetComponent(e, 0);
    return out;
  }
  if (field == "displacement") {  // cell mean of the nodal displacement magnitude
    vtkDataArray* u = need(g->GetPointData()->GetArray("displacement"), "displacement");
    for (vtkIdType e = 0; e < n; ++e) {
      vtkCell* cell = g->GetCell(e);
      double s = 0;
      for (vtkIdType i = 0; i < cell->GetNumberOfPoints(); ++i) {
        double v[3];
        u->GetTuple(cell->GetPointId(i), v);
        s += std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      }
      out[e] = s / static_cast<double>(cell->GetNumberOfPoints());
    }
    return out;
  }
  std::string list;
  for (const auto& f : stress_fields()) list += (list.empty() ? "" : ", ") + f;
  fail("unknown field '{}' (known: {})", field, list);
}

namespace {
// 20 well-separated colours (Tableau 20), for fragment ids.
const unsigned char kPalette[20][3] = {{31, 119, 180},  {255, 127, 14},  {44, 160, 44},   {214, 39, 40},
                                       {148, 103, 189}, {140, 86, 75},   {227, 119, 194}, {127, 127, 127},
                                       {188, 189, 34},  {23, 190, 207},  {174, 199, 232}, {255, 187, 120},
                                       {152, 223, 138}, {255, 152, 150}, {197, 176, 213}, {196, 156, 148},
                                       {247, 182, 210}, {199, 199, 199}, {219, 219, 141}, {158, 218, 229}};

// Points drawn with their displacement u magnified m times: x - u + m u.
vtkSmartPointer<vtkPoints> magnified(vtkPoints* x, vtkDataArray* u, double m) {
  auto pts = vtkSmartPointer<vtkPoints>::New();
  pts->DeepCopy(x);
  for (vtkIdType i = 0; i < pts->GetNumberOfPoints(); ++i) {
    double p[3], d[3];
    pts->GetPoint(i, p);
    u->GetTuple(i, d);
    for (int k = 0; k < 3; ++k) p[k] += (m - 1.0) * d[k];
    pts->SetPoint(i, p);
  }
  return pts;
}

// Text in pixels: a 1/`per` of the image's height, or of the height a 16:9 image of its width
// would have, whichever is more: a wide, low image (the impact beam's 1280 x 400) has its
// text sized as a 1280 x 720 one's, not shrunk to the smallest.
int text_px(const ViewOptions& o, int per, int least) {
  return std::max(least, std::max(o.height, o.width * 9 / 16) / per);
}

void place_camera(vtkRenderer* r, const ViewOptions& o) {
  const double* b = o.bounds;
  const double c[3] = {0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])};
  const double diag =
      std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
  double dir[3] = {0, 0, 1}, up[3] = {0, 1, 0};
  if (o.camera == "front")
    dir[0] = 0, dir[1] = 0, dir[2] = 1;
  else if (o.camera == "back")
    dir[0] = 0, dir[1] = 0, dir[2] = -1;
  else if (o.camera == "top")
    dir[0] = 0, dir[1] = 1, dir[2] = 0, up[1] = 0, up[2] = -1;
  else if (o.camera == "side")
    dir[0] = 1, dir[1] = 0, dir[2] = 0;
  else if (o.camera == "iso")
    dir[0] = 1, dir[1] = 0.8, dir[2] = 1.2;
  else
    fail("unknown camera preset '{}' (known: front, back, top, side, iso)", o.camera);
  const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  vtkCamera* cam = r->GetActiveCamera();
  cam->SetFocalPoint(c);
  cam->SetPosition(c[0] + 3 * diag * dir[0] / len, c[1] + 3 * diag * dir[1] / len, c[2] + 3 * diag * dir[2] / len);
  cam->SetViewUp(up);
  cam->ParallelProjectionOn();  // no perspective: crack patterns compare pixel to pixel
  const double aspect = static_cast<double>(o.width) / o.height;
  DSPDEM_CHECK(o.fit == "diagonal" || o.fit == "box", "unknown framing fit '{}' (known: diagonal, box)", o.fit);
  if (o.fit == "box" && o.camera != "iso") {
    // The box's face the camera sees fills the image with a margin of 30 % (a long beam across
    // a wide image); the diagonal's sphere below fits any camera, and pieces flying off.
    const double ex = b[1] - b[0], ey = b[3] - b[2], ez = b[5] - b[4];
    const double across = o.camera == "side" ? ez : ex, up_down = o.camera == "top" ? ez : ey;
    cam->SetParallelScale(0.5 * 1.3 * std::max(up_down, across / aspect));
  } else {
    cam->SetParallelScale(0.55 * diag / std::min(1.0, aspect) * 0.9);
  }
  cam->SetClippingRange(0.1 * diag, 10 * diag);
}
}  // namespace

struct FrameRenderer::Impl {
  ViewOptions opt;
  OffscreenWindow win;
  vtkNew<vtkRenderer> ren;
  vtkNew<vtkActor> actor, context_actor, crack_lines, wall_actor, wall_edge_actor;
  vtkNew<vtkPolyDataMapper> mapper, context_mapper, wall_mapper, wall_edge_mapper;
  vtkNew<vtkFeatureEdges> wall_edges;
  vtkNew<vtkLookupTable> lut;
  vtkNew<vtkScalarBarActor> bar;
  vtkNew<vtkTextActor> time_text, magnify_text, scale_text, bar_title, key_cracks, key_bodies;
  vtkNew<vtkActor2D> scale_actor;
  vtkNew<vtkPolyDataMapper2D> scale_mapper;
  FieldDisplay display;
  explicit Impl(const ViewOptions& o) : opt(o), win(o.width, o.height), display(field_display(o.field)) {}
  // A scale bar in the top-right corner: a round length (1, 2 or 5 x 10^k) about a sixth of
  // the image wide, with end ticks and its length in mm. Parallel projection: one pixel is
  // 2 ParallelScale / height in the view plane, on every frame (the camera never moves).
  void add_scale_bar() {
    const ViewOptions& o = opt;
    const double per_px = 2 * ren->GetActiveCamera()->GetParallelScale() / o.height;
    const double len = nice_length(o.width / 6.0 * per_px);
    if (!(len > 0)) return;
    const double px = len / per_px, font = text_px(o, 30, 12);
    const double x1 = o.width - 0.03 * o.width, x0 = x1 - px, y = o.height - 10 - 0.5 * font, tick = 0.35 * font;
    vtkNew<vtkPoints> pts;
    for (const auto& [x, yy] :
         {std::pair{x0, y - tick}, {x0, y + tick}, {x0, y}, {x1, y}, {x1, y - tick}, {x1, y + tick}})
      pts->InsertNextPoint(x, yy, 0);
    vtkNew<vtkCellArray> lines;
    const vtkIdType seg[3][2] = {{0, 1}, {2, 3}, {4, 5}};
    for (const auto& sg : seg) lines->InsertNextCell(2, sg);
    vtkNew<vtkPolyData> marks;
    marks->SetPoints(pts);
    marks->SetLines(lines);
    scale_mapper->SetInputData(marks);
    scale_actor->SetMapper(scale_mapper);
    scale_actor->GetProperty()->SetColor(0.1, 0.1, 0.1);
    scale_actor->GetProperty()->SetLineWidth(std::max(2.0, o.height / 360.0));
    ren->AddViewProp(scale_actor);
    const double mm = 1e3 * len;
    scale_text->SetInput((mm >= 1000 ? fmt::format("{:g} m", mm / 1000) : fmt::format("{:g} mm", mm)).c_str());
    scale_text->GetTextProperty()->SetFontSize(static_cast<int>(font));
    scale_text->GetTextProperty()->SetColor(0.1, 0.1, 0.1);
    scale_text->GetTextProperty()->SetJustificationToRight();
    scale_text->SetPosition(x0 - 0.5 * font, y - 0.5 * font);
    ren->AddViewProp(scale_text);
  }
};

FrameRenderer::FrameRenderer(const ViewOptions& o) : impl_(new Impl(o)) {
  Impl& s = *impl_;
  if (o.view != "stress" && o.view != "fragments" && o.view != "cracks")
    fail("unknown view '{}' (known: stress, fragments, cracks)", o.view);
  s.ren->SetBackground(o.background.data());
  s.win.add_renderer(s.ren);
  s.actor->SetMapper(s.mapper);
  s.ren->AddActor(s.actor);
  // Colours and labels in display units (MPa, mm); the range is given in the field's own.
  const double lo = o.range[0] * s.display.scale, hi = o.range[1] * s.display.scale;
  fill_lookup_table(s.lut, s.display.is_signed, lo, hi);
  s.time_text->GetTextProperty()->SetFontSize(text_px(o, 30, 12));
  s.time_text->GetTextProperty()->SetColor(0.1, 0.1, 0.1);
  s.time_text->SetPosition(10, o.height - 10 - text_px(o, 30, 12));
  s.ren->AddViewProp(s.time_text);
  // A magnified drawing says so on a line of its own below the time: the scale bar holds for
  // the bodies' places, not for their displacements.
  s.magnify_text->GetTextProperty()->ShallowCopy(s.time_text->GetTextProperty());
  s.magnify_text->SetPosition(10, o.height - 14 - 2 * s.time_text->GetTextProperty()->GetFontSize());
  s.magnify_text->SetVisibility(false);
  s.ren->AddViewProp(s.magnify_text);
  if (o.view == "stress") {
    s.mapper->SetLookupTable(s.lut);
    s.mapper->SetScalarRange(lo, hi);
    s.mapper->SetScalarModeToUseCellFieldData();
    s.mapper->SelectColorArray("field");
    s.mapper->ScalarVisibilityOn();
    s.bar->SetLookupTable(s.lut);
    // The bar's own title sits under its labels with no gap, and touches them at small sizes
    // (640 x 360): it is drawn above the bar instead, whose top is the top of its frame.
    s.bar->SetTitle("");
    // Round tick values (2, 2.5 ... MPa, not 2.347): the bar's own labels split the range evenly.
    const std::vector<double> ticks = nice_ticks(lo, hi, 6);
    if (ticks.size() >= 2) {
      vtkNew<vtkDoubleArray> labels;
      for (double t : ticks) labels->InsertNextValue(t);
      s.bar->SetUseCustomLabels(true);
      s.bar->SetCustomLabels(labels);
      s.bar->SetLabelFormat("%g");
    } else {
      s.bar->SetNumberOfLabels(5);
    }
    // Horizontal along the bottom: it never covers the bodies, whatever their shape.
    s.bar->SetOrientationToHorizontal();
    constexpr double bar_bottom = 0.01, bar_height = 0.14;  // of the image's height
    s.bar->SetPosition(0.2, bar_bottom);
    s.bar->SetWidth(0.6);
    s.bar->SetHeight(bar_height);
    s.bar->SetTextPositionToPrecedeScalarBar();
    s.bar->UnconstrainedFontSizeOn();
    // Upright, plain labels (VTK's default is bold italic with a shadow), as large as the title.
    const int font = text_px(o, 40, 10);
    vtkTextProperty* labels = s.bar->GetLabelTextProperty();
    labels->SetFontSize(font);
    labels->SetColor(0.1, 0.1, 0.1);
    labels->ItalicOff();
    labels->BoldOff();
    labels->ShadowOff();
    s.ren->AddViewProp(s.bar);
    s.bar_title->SetInput(s.display.title.c_str());
    vtkTextProperty* title = s.bar_title->GetTextProperty();
    title->SetFontSize(font);
    title->SetColor(0.1, 0.1, 0.1);
    title->SetJustificationToCentered();
    title->SetVerticalJustificationToBottom();
    s.bar_title->SetPosition(0.5 * o.width, (bar_bottom + bar_height) * o.height + 0.3 * font);
    s.ren->AddViewProp(s.bar_title);
  } else {
    s.mapper->SetScalarModeToUseCellFieldData();
    s.mapper->SelectColorArray("colors");
    s.mapper->SetColorModeToDirectScalars();
    s.mapper->ScalarVisibilityOn();
  }
  if (o.view == "cracks") {
    s.mapper->ScalarVisibilityOff();
    s.actor->GetProperty()->SetColor(0.75, 0.75, 0.75);
    s.actor->GetProperty()->SetOpacity(0.2);
    s.context_actor->SetMapper(s.context_mapper);
    s.context_actor->GetProperty()->SetColor(0.8, 0.05, 0.05);
    s.ren->AddActor(s.context_actor);
    // Their edges too, as lines of their own in the same red: a crack seen edge-on (the impact
    // beam's cracks across the section, seen along the width) has no area in the image and was
    // not drawn; the surface's own edges are drawn by a shader that emits nothing for a
    // triangle seen exactly edge-on.
    s.crack_lines->SetMapper(s.context_mapper);
    s.crack_lines->GetProperty()->SetRepresentationToWireframe();
    s.crack_lines->GetProperty()->SetColor(0.8, 0.05, 0.05);
    s.crack_lines->GetProperty()->SetLineWidth(std::max(1.0f, static_cast<float>(o.height) / 360.0f));
    s.crack_lines->GetProperty()->LightingOff();
    s.ren->AddActor(s.crack_lines);
    // The key, bottom left, each line in the colour it names, the grey darker than the
    // translucent bodies look, to be read (a panel of a montage too: a figure is cut from it
    // on its own).
    const int font = text_px(o, 40, 10);
    s.key_cracks->SetInput("broken joints");
    s.key_bodies->SetInput("bodies and open cracks (translucent grey)");
    int line = 0;
    for (vtkTextActor* key : {s.key_bodies.GetPointer(), s.key_cracks.GetPointer()}) {
      key->GetTextProperty()->SetFontSize(font);
      key->SetPosition(10, 10 + (line++) * 1.4 * font);
      s.ren->AddViewProp(key);
    }
    s.key_cracks->GetTextProperty()->SetColor(0.8, 0.05, 0.05);
    s.key_bodies->GetTextProperty()->SetColor(0.45, 0.45, 0.45);
  }
  s.wall_mapper->ScalarVisibilityOff();
  s.wall_actor->SetMapper(s.wall_mapper);
  s.wall_actor->GetProperty()->SetColor(0.45, 0.5, 0.58);
  s.wall_actor->GetProperty()->SetOpacity(0.22);
  s.wall_actor->VisibilityOff();
  s.ren->AddActor(s.wall_actor);
  // A wall seen edge-on (a jaw's arc or a plate from the front) is a translucent sliver: its
  // outline and sharp edges, drawn as lines, show where it is.
  s.wall_edges->BoundaryEdgesOn();
  s.wall_edges->FeatureEdgesOn();
  s.wall_edges->SetFeatureAngle(60);
  s.wall_edges->NonManifoldEdgesOff();
  s.wall_edges->ManifoldEdgesOff();
  s.wall_edges->ColoringOff();
  s.wall_edge_mapper->SetInputConnection(s.wall_edges->GetOutputPort());
  s.wall_edge_mapper->ScalarVisibilityOff();
  s.wall_edge_actor->SetMapper(s.wall_edge_mapper);
  s.wall_edge_actor->GetProperty()->SetColor(0.3, 0.34, 0.4);
  s.wall_edge_actor->GetProperty()->SetOpacity(0.7);
  s.wall_edge_actor->GetProperty()->SetLineWidth(std::max(1.5, o.height / 480.0));
  s.wall_edge_actor->GetProperty()->LightingOff();
  s.wall_edge_actor->VisibilityOff();
  s.ren->AddActor(s.wall_edge_actor);
  if (o.edges && o.view != "cracks") {
    s.actor->GetProperty()->EdgeVisibilityOn();
    s.actor->GetProperty()->SetEdgeColor(0.2, 0.2, 0.2);
  }
  place_camera(s.ren, o);
  if (o.view == "stress") {
    // Leave the bottom strip to the horizontal scalar bar: shift the picture up a little.
    vtkCamera* cam = s.ren->GetActiveCamera();
    cam->SetParallelScale(cam->GetParallelScale() * 1.12);
    cam->SetWindowCenter(0.0, -0.16);
  }
  if (o.scale_bar) s.add_scale_bar();
}

FrameRenderer::~FrameRenderer() { delete impl_; }

std::string FrameRenderer::gl_info() const { return impl_->win.gl_info(); }

vtkSmartPointer<vtkImageData> FrameRenderer::render(vtkUnstructuredGrid* frame, double time, const std::string& file,
                                                    vtkUnstructuredGrid* joints, vtkPolyData* walls) {
  Impl& s = *impl_;
  const ViewOptions& o = s.opt;
  s.wall_actor->SetVisibility(walls != nullptr);
  s.wall_edge_actor->SetVisibility(walls != nullptr);
  if (walls) {
    s.wall_mapper->SetInputData(walls);
    s.wall_edges->SetInputData(walls);
  }
  // The magnification drawn: the cracks view moves its joints with the bodies, by their
  // displacement, which runs written before the joints' files had it lack; such a run's cracks
  // view is drawn unmagnified rather than with its cracks beside the gaps they opened.
  double magnify = o.magnify;
  if (o.view == "cracks") {
    if (!joints || !joints->GetCellData()->GetArray("state"))
      fail("the cracks view needs the joints dataset, which frame '{}' does not have (the run has no joints)", file);
    vtkDataArray* ju = joints->GetPointData()->GetArray("displacement");
    if (!ju) magnify = 1.0;
    // Broken joints (state 2), drawn red over the translucent bodies.
    vtkDataArray* state = joints->GetCellData()->GetArray("state");
    vtkNew<vtkPolyData> cracks;
    vtkNew<vtkCellArray> polys;
    cracks->SetPoints(magnify != 1.0 ? magnified(joints->GetPoints(), ju, magnify).GetPointer() : joints->GetPoints());
    for (vtkIdType c = 0; c < joints->GetNumberOfCells(); ++c)
      if (state->GetComponent(c, 0) > 1.5) {
        vtkIdList* ids = joints->GetCell(c)->GetPointIds();
        polys->InsertNextCell(ids);
      }
    cracks->SetPolys(polys);
    s.context_mapper->SetInputData(cracks);
    s.context_mapper->ScalarVisibilityOff();
  }
  vtkNew<vtkUnstructuredGrid> g;
  g->ShallowCopy(frame);
  // Magnified displacement: x_draw = x - u + m u.
  if (magnify != 1.0) {
    vtkDataArray* u = g->GetPointData()->GetArray("displacement");
    if (!u) fail("frame '{}' has no displacement array, needed for magnify = {}", file, magnify);
    g->SetPoints(magnified(frame->GetPoints(), u, magnify));
  }
  if (o.view == "stress") {
    const std::vector<double> v = field_values(g, o.field, file);
    vtkNew<vtkDoubleArray> a;
    a->SetName("field");
    a->SetNumberOfTuples(static_cast<vtkIdType>(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) a->SetValue(static_cast<vtkIdType>(i), v[i] * s.display.scale);
    g->GetCellData()->AddArray(a);
  } else if (o.view == "fragments") {
    vtkDataArray* id = g->GetCellData()->GetArray("fragment");
    if (!id) id = g->GetCellData()->GetArray("body");
    if (!id) fail("frame '{}' has neither a 'fragment' nor a 'body' array: the {} view needs one", file, o.view);
    vtkNew<vtkUnsignedCharArray> c;
    c->SetName("colors");
    c->SetNumberOfComponents(3);
    c->SetNumberOfTuples(g->GetNumberOfCells());
    // Colour by size rank (cells per piece, ties by id): the largest piece palette[0], the
    // next palette[1], and so on, so the pieces a crack pattern is about always differ in
    // colour (a hash of the id, used before, gave the two halves of a split disc one colour).
    // A piece keeps its colour while its rank does; beyond the 20th the palette wraps.
    const vtkIdType nc = g->GetNumberOfCells();
    std::map<long, long> cells;
    for (vtkIdType e = 0; e < nc; ++e) ++cells[std::lround(id->GetComponent(e, 0))];
    std::vector<std::pair<long, long>> by_size(cells.begin(), cells.end());
    std::stable_sort(by_size.begin(), by_size.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    for (std::size_t r = 0; r < by_size.size(); ++r) cells[by_size[r].first] = static_cast<long>(r);  // now the rank
    std::vector<int> rank(static_cast<std::size_t>(nc));
    for (vtkIdType e = 0; e < nc; ++e) rank[e] = static_cast<int>(cells[std::lround(id->GetComponent(e, 0))]);
    // Pieces that touch: a point of one within a hair (1e-5 of the framing diagonal, far
    // below an element, far above rounding) of a point of another.
    std::set<std::pair<int, int>> touching;
    if (by_size.size() > 1) {
      std::vector<int> point_rank(static_cast<std::size_t>(g->GetNumberOfPoints()), -1);
      for (vtkIdType e = 0; e < nc; ++e) {
        vtkIdType np = 0;
        const vtkIdType* pts = nullptr;
        g->GetCellPoints(e, np, pts);
        for (vtkIdType k = 0; k < np; ++k) point_rank[pts[k]] = rank[e];
      }
      const double* b = o.bounds;
      const double tol = 1e-5 * std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
                                          (b[5] - b[4]) * (b[5] - b[4]));
      vtkNew<vtkStaticPointLocator> loc;
      loc->SetDataSet(g);
      loc->BuildLocator();
      vtkNew<vtkIdList> near;
      for (vtkIdType p = 0; p < g->GetNumberOfPoints(); ++p) {
        if (point_rank[p] < 0) continue;
        loc->FindPointsWithinRadius(tol, g->GetPoint(p), near);
        for (vtkIdType k = 0; k < near->GetNumberOfIds(); ++k) {
          const int q = point_rank[near->GetId(k)];
          if (q >= 0 && q != point_rank[p]) touching.emplace(std::min(q, point_rank[p]), std::max(q, point_rank[p]));
        }
      }
    }
    const std::vector<int> colour =
        piece_colours(by_size.size(), std::vector<std::pair<int, int>>(touching.begin(), touching.end()), 20);
    for (vtkIdType e = 0; e < nc; ++e) c->SetTypedTuple(e, kPalette[colour[static_cast<std::size_t>(rank[e])]]);
    g->GetCellData()->AddArray(c);
  }
  vtkNew<vtkDataSetSurfaceFilter> surf;
  if (o.cut != "none") {
    const double* b = o.bounds;
    vtkNew<vtkPlane> plane;
    plane->SetOrigin(0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]));
    if (o.cut == "x")
      plane->SetNormal(1, 0, 0);
    else if (o.cut == "y")
      plane->SetNormal(0, 1, 0);
    else if (o.cut == "z")
      plane->SetNormal(0, 0, 1);
    else
      fail("unknown cut '{}' (known: none, x, y, z)", o.cut);
    vtkNew<vtkTableBasedClipDataSet> clip;
    clip->SetInputData(g);
    clip->SetClipFunction(plane);
    clip->InsideOutOn();  // keep the half below the plane
    surf->SetInputConnection(clip->GetOutputPort());
  } else {
    surf->SetInputData(g);
  }
  surf->Update();
  // Joints split every element from its neighbours, so the surface holds every element face
  // twice. Keep only faces that are not matched by a coincident face: the outer envelope and
  // the opened cracks. Points within 1e-4 of the diagonal are one: joint openings before
  // failure are smaller. In the cracks view stacked translucent layers would hide the cracks;
  // in the others the hidden faces showed through the hair-wide seams between the outer
  // faces of neighbouring elements (each with its own nodes) as stray dark pixels, which
  // merged points close.
  s.mapper->SetInputData(unmatched_faces(surf->GetOutput(), 1e-4));
  const std::string t = fmt::format("t = {:.4g} ms", time * 1e3);
  s.magnify_text->SetVisibility(magnify != 1.0);
  if (magnify != 1.0) s.magnify_text->SetInput(fmt::format("displacement x{:g}", magnify).c_str());
  const std::string& who = o.label.empty() ? o.title : o.label;
  s.time_text->SetInput((who.empty() ? t : who + "   " + t).c_str());
  return s.win.capture();
}

}  // namespace dspdem::render
