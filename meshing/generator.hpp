// Mesh generators for the benchmark geometries, on the gmsh C++ API, and their registry.
// A case names a generator and its parameters ([mesh] generator = "...", [mesh.<name>]);
// each generator declares its parameters (type, default, range, unit, doc) beside its code
// (<name>_keys() in meshing/<name>.cpp), the case reader validates them; a generator only checks relations
// between parameters (a notch deeper than the beam, a size larger than the part) and
// reports them naming the key.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "core/key_spec.hpp"
#include "mesh/mesh.hpp"

namespace dspdem::meshing {

/// Validated parameters of one generator.
struct Params {
  std::string generator;
  std::map<std::string, double> num;
  std::map<std::string, std::string> str;

  double operator[](const std::string& key) const;
  const std::string& text(const std::string& key) const;
  /// Sorted key=value list with full precision: the identity of the mesh for caching.
  std::string canonical() const;
};

/// Throws Error "mesh.<generator>.<key> = <value>: <why>".
[[noreturn]] void param_error(const Params& p, const std::string& key, const std::string& why);

/// The most elements a generator is let make: a count past it comes from a mistyped size or
/// count (gmsh went on filling the machine's memory, then aborted).
inline constexpr double kMostElements = 1e8;
/// Before meshing: param_error naming `key` when a uniform size `h` over `volume` [m^3] would
/// give more than kMostElements tetrahedra, at 4 a size cubed (gmsh's count for the Brazilian
/// disc's default size is 4.7: a target_elements within its range is not refused as its size is
/// rescaled). A guard against a mistyped size, not an estimate of the mesh.
void check_tet_count(const Params& p, const std::string& key, double volume, double h);
/// The same for a size growing linearly from `fine` at lines of total length `length` on the
/// body's surface to `coarse` at `reach` from them (set_graded_size): 4 tetrahedra a size
/// cubed over the half cylinders round the lines, 2 pi length reach^2 / (fine coarse^2), which
/// grows as 1/fine (a mistyped load_size of 1e-9 m gave gmsh 2e10 elements to make). A
/// refinement at a point or a notch tip needs none: its count grows as log(coarse / fine).
void check_graded_count(const Params& p, const std::string& key, double length, double fine, double coarse,
                        double reach);
/// param_error naming `key` when `count` elements, counted as `how`, exceed kMostElements.
void check_count(const Params& p, const std::string& key, double count, const std::string& how);

struct Generator {
  const char* name;
  const char* doc;                            ///< geometry, groups, and where defaults come from
  void (*build)(const Params&);               ///< builds and meshes the current gmsh model, adds groups
  const char* count_group;                    ///< group counted for target_elements (null: no target)
  const std::vector<schema::Key>& (*keys)();  ///< its [mesh.<name>] parameters
};

/// All generators, by name.
const std::vector<Generator>& registry();
/// The generator called `name`; throws Error listing the known names otherwise.
const Generator& find_generator(const std::string& name);

/// Runs the generator in a fresh gmsh model and returns the mesh; if `msh_path` is not
/// empty, also writes the gmsh file there (through a temporary name).
Mesh generate(const Params& p, const std::string& msh_path = "");

/// What generate() is meshing now ("" when nothing): gmsh throws some errors inside its own
/// OpenMP regions, where no handler catches them and the process ends in std::terminate;
/// the program's terminate handler names the mesh from this.
std::string meshing_now();

/// Returns the mesh from the cache when a file for the same generator, parameters and gmsh
/// version exists in `cache_dir`, else generates and stores it. `cached` tells which.
Mesh load_or_generate(const Params& p, const std::string& cache_dir, bool* cached = nullptr,
                      std::string* path = nullptr);

/// Default cache folder: $DSPDEM_MESH_CACHE, else $XDG_CACHE_HOME/dspdem/meshes, else
/// $HOME/.cache/dspdem/meshes.
std::string default_cache_dir();

// Helpers shared by generators ---------------------------------------------------------
/// Adds a named physical group of the given entities.
void add_group(int dim, const std::vector<int>& tags, const std::string& name);
/// Entities of dimension `dim` inside the box (with a tolerance `eps` on every side).
std::vector<int> entities_in_box(int dim, double x0, double y0, double z0, double x1, double y1, double z1,
                                 double eps = 1e-6);
/// Sets the target mesh size on every point of the given volumes.
void set_volume_size(const std::vector<int>& volumes, double size);
/// Grades the size inside the given volumes (their faces and curves included) from size_min
/// where gmsh field `distance` (already added, any tag below 100) reads 0 up to size_max where
/// it reads dist_max and beyond; other volumes keep their own sizes. The background mesh.
void set_graded_size(int distance, double size_min, double size_max, double dist_max, const std::vector<int>& volumes);

}  // namespace dspdem::meshing
