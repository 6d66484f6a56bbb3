#include "render/plot.hpp"

#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextActor.h>
#include <vtkContextScene.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include <fstream>
#include <sstream>
#include <string_view>
#include <utility>

#include "core/error.hpp"
#include "render/offscreen.hpp"

namespace dspdem::render {

void read_csv(const std::string& path, std::vector<std::string>& names, std::vector<std::vector<double>>& cols) {
  std::ifstream f(path);
  DSPDEM_CHECK(f.good(), "CSV file '{}' cannot be read", path);
  std::string line;
  DSPDEM_CHECK(static_cast<bool>(std::getline(f, line)), "CSV file '{}' is empty", path);
  names.clear();
  std::stringstream hs(line);
  for (std::string n; std::getline(hs, n, ',');) names.push_back(n);
  cols.assign(names.size(), {});
  long row = 1;
  while (std::getline(f, line)) {
    ++row;
    if (line.empty()) continue;
    std::stringstream ls(line);
    std::size_t c = 0;
    for (std::string v; std::getline(ls, v, ','); ++c) {
      DSPDEM_CHECK(c < names.size(), "CSV file '{}' line {}: more values than header columns", path, row);
      try {
        cols[c].push_back(std::stod(v));
      } catch (...) {
        fail("CSV file '{}' line {}: '{}' is not a number", path, row, v);
      }
    }
    DSPDEM_CHECK(c == names.size(), "CSV file '{}' line {}: {} values for {} columns", path, row, c, names.size());
  }
}

namespace {
// Tableau's ten: a run's energy plot has thirteen curves, a sweep one per run.
const unsigned char many_colors[10][3] = {{31, 119, 180},  {255, 127, 14}, {44, 160, 44},   {214, 39, 40},
                                          {148, 103, 189}, {140, 86, 75},  {227, 119, 194}, {127, 127, 127},
                                          {188, 189, 34},  {23, 190, 207}};

// An off-screen window holding one XY chart on a white background.
struct ChartWindow {
  OffscreenWindow win;
  vtkNew<vtkRenderer> ren;
  vtkNew<vtkChartXY> chart;
  vtkNew<vtkContextScene> scene;
  vtkNew<vtkContextActor> actor;
  ChartWindow(int width, int height) : win(width, height) {
    ren->SetBackground(1, 1, 1);
    win.add_renderer(ren);
    scene->AddItem(chart);
    actor->SetScene(scene);
    ren->AddActor(actor);
    scene->SetRenderer(ren);
  }
};

// The k-th curve's colour; past ten, the colours again, dotted and then dash-dotted, so that no
// two curves of a plot look alike (the energy plot's thirteen repeated every fifth colour).
void set_style(vtkPlot* p, std::size_t k) {
  const unsigned char* c = many_colors[k % 10];
  p->SetColor(c[0], c[1], c[2], 255);
  p->SetWidth(2.0);
  const int again = static_cast<int>(k / 10) % 3;
  if (again > 0) p->GetPen()->SetLineType(again == 1 ? vtkPen::DOT_LINE : vtkPen::DASH_DOT_LINE);
}

// The legend beside the plot, right of it, not on it: inside, VTK puts it in the top right
// corner, where a load curve has its peak (the disc's) and a ledger its largest terms.
void show_legend_beside(vtkChartXY* chart) {
  chart->SetShowLegend(true);
  vtkChartLegend* l = chart->GetLegend();
  l->SetInline(false);
  l->SetHorizontalAlignment(vtkChartLegend::RIGHT);
  l->SetVerticalAlignment(vtkChartLegend::TOP);
}

// A column's unit where its name says it: series.csv's "time", or a report table's suffix
// ("time_ms", "load_kN", "error_pct"); "" where the name gives none.
std::string column_unit(const std::string& column) {
  if (column == "time") return "s";
  static const std::pair<const char*, const char*> suffixes[] = {
      {"_ms", "ms"},   {"_s", "s"}, {"_mm", "mm"}, {"_m", "m"},   {"_kN", "kN"},  {"_N", "N"},
      {"_MPa", "MPa"}, {"_J", "J"}, {"_kg", "kg"}, {"_pct", "%"}, {"_deg", "deg"}};
  for (const auto& [suffix, unit] : suffixes) {
    const std::string_view s(suffix);
    if (column.size() > s.size() && column.compare(column.size() - s.size(), s.size(), s) == 0) return unit;
  }
  return "";
}

// An axis title with its unit where the column's name gives one: "time_ms" reads "time [ms]".
std::string axis_title(const std::string& column) {
  const std::string u = column_unit(column);
  if (u.empty()) return column;
  if (column == "time") return "time [s]";
  const std::size_t cut = column.rfind('_');
  return column.substr(0, cut) + " [" + u + "]";
}

// The left axis's title when the plot gives none: one curve's own, or the unit its curves
// share, so that a plot of several curves is not left with a bare axis.
std::string y_axis_title(const std::vector<std::string>& y) {
  if (y.size() == 1) return axis_title(y.front());
  const std::string u = y.empty() ? "" : column_unit(y.front());
  for (const auto& c : y)
    if (column_unit(c) != u) return "";
  return u.empty() ? "" : "[" + u + "]";
}

std::size_t column(const std::vector<std::string>& names, const std::string& name, const std::string& file) {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return i;
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  fail("CSV file '{}' has no column '{}' (columns: {})", file, name, list);
}

void add_lines(vtkChartXY* chart, const std::string& csv, const PlotSpec& spec, bool reference) {
  std::vector<std::string> names;
  std::vector<std::vector<double>> cols;
  read_csv(csv, names, cols);
  const std::size_t xi = column(names, spec.x, csv);
  vtkNew<vtkTable> t;
  vtkNew<vtkDoubleArray> xa;
  xa->SetName(spec.x.c_str());
  t->AddColumn(xa);
  std::vector<std::size_t> yi;
  for (const auto& y : spec.y) {
    yi.push_back(column(names, y, csv));
    vtkNew<vtkDoubleArray> ya;
    ya->SetName((reference ? y + " (reference)" : y).c_str());
    t->AddColumn(ya);
  }
  t->SetNumberOfRows(static_cast<vtkIdType>(cols[xi].size()));
  for (std::size_t r = 0; r < cols[xi].size(); ++r) {
    t->SetValue(static_cast<vtkIdType>(r), 0, cols[xi][r]);
    for (std::size_t k = 0; k < yi.size(); ++k)
      t->SetValue(static_cast<vtkIdType>(r), static_cast<vtkIdType>(k + 1), cols[yi[k]][r]);
  }
  for (std::size_t k = 0; k < yi.size(); ++k) {
    vtkPlot* p = chart->AddPlot(vtkChart::LINE);
    p->SetInputData(t, 0, static_cast<vtkIdType>(k + 1));
    set_style(p, k);
    // A reference in its curve's colour, dashed: with several, each is told by its colour.
    if (reference) p->GetPen()->SetLineType(vtkPen::DASH_LINE);
  }
}
}  // namespace

void plot_csv(const std::string& csv, const PlotSpec& spec, const std::string& png) {
  DSPDEM_CHECK(!spec.y.empty(), "plot of '{}': no y column given", csv);
  ChartWindow cw(spec.width, spec.height);
  vtkChartXY* chart = cw.chart;
  add_lines(chart, csv, spec, false);
  if (!spec.reference_csv.empty()) add_lines(chart, spec.reference_csv, spec, true);
  show_legend_beside(chart);
  chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(spec.x_title.empty() ? axis_title(spec.x) : spec.x_title);
  chart->GetAxis(vtkAxis::LEFT)->SetTitle(!spec.y_title.empty() ? spec.y_title : y_axis_title(spec.y));
  chart->SetTitle(spec.title.empty() ? csv : spec.title);
  cw.win.write_png(png);
}

void plot_curves(const std::vector<Curve>& curves, const std::string& x_title, const std::string& y_title,
                 const std::string& title, const std::string& png, bool log_x, int width, int height) {
  DSPDEM_CHECK(!curves.empty(), "plot '{}': no curve given", png);
  ChartWindow cw(width, height);
  vtkChartXY* chart = cw.chart;
  std::vector<vtkSmartPointer<vtkTable>> tables;  // a table per curve: each has its own x
  for (std::size_t k = 0; k < curves.size(); ++k) {
    const Curve& c = curves[k];
    DSPDEM_CHECK(c.x.size() == c.y.size(), "plot '{}': curve '{}' has {} x and {} y values", png, c.name, c.x.size(),
                 c.y.size());
    if (c.x.empty()) continue;
    auto t = vtkSmartPointer<vtkTable>::New();
    vtkNew<vtkDoubleArray> xa, ya;
    xa->SetName((c.name + " x").c_str());
    ya->SetName(c.name.c_str());
    t->AddColumn(xa);
    t->AddColumn(ya);
    t->SetNumberOfRows(static_cast<vtkIdType>(c.x.size()));
    for (std::size_t r = 0; r < c.x.size(); ++r) {
      DSPDEM_CHECK(!log_x || c.x[r] > 0, "plot '{}': curve '{}' has x = {} on a log axis", png, c.name, c.x[r]);
      t->SetValue(static_cast<vtkIdType>(r), 0, c.x[r]);
      t->SetValue(static_cast<vtkIdType>(r), 1, c.y[r]);
    }
    vtkPlot* p = chart->AddPlot(vtkChart::LINE);
    p->SetInputData(t, 0, 1);
    set_style(p, k);
    tables.push_back(t);
  }
  show_legend_beside(chart);
  chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(x_title);
  chart->GetAxis(vtkAxis::LEFT)->SetTitle(y_title);
  if (log_x) chart->GetAxis(vtkAxis::BOTTOM)->SetLogScale(true);
  chart->SetTitle(title);
  cw.win.write_png(png);
}

}  // namespace dspdem::render
