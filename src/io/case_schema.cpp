#include "io/case_schema.hpp"

#include <fmt/format.h>

#include <limits>
#include <string>

#include "meshing/generator.hpp"

namespace dspdem::schema {

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();
using T = Type;
}  // namespace

const std::vector<const char*>& sections() {
  static const std::vector<const char*> s = [] {
    std::vector<const char*> out = {"case", "mesh"};
    static std::vector<std::string> names;  // keeps the "mesh.<name>" strings alive
    names.reserve(meshing::registry().size());
    for (const auto& g : meshing::registry()) names.push_back(std::string("mesh.") + g.name);
    for (const auto& n : names) out.push_back(n.c_str());
    for (const char* r : {"physics", "contact", "materials.<name>", "bodies[]", "boundary[]", "initial[]", "walls[]",
                          "time", "output", "monitors[]", "render", "checks"})
      out.push_back(r);
    return out;
  }();
  return s;
}

// clang-format off
namespace {
const std::vector<Key>& general_keys() {
  static const std::vector<Key> k = {
    {"case", "name", T::String, "auto", 0, 0, false, false, "", nullptr, "Case name used in outputs (the run's folder under results/: no `/` or `\\`, not empty, not starting with `.`); defaults to the file name without extension."},
    {"case", "scene", T::String, "auto", 0, 0, false, false, "", nullptr, "Benchmark scene whose report `dspdem report` writes (`dspdem scenes` lists them); default: the one made for the mesh generator, if any."},
    {"case", "description", T::String, "\"\"", 0, 0, false, false, "", nullptr, "Free text: what the case checks, sources of its numbers and choices made."},
    {"mesh", "file", T::String, "auto", 0, 0, false, false, "", nullptr, "Mesh file (.msh v2/v4, or a .geo script that gmsh meshes in 3D), relative to the case file. Give either file or generator."},
    {"mesh", "generator", T::String, "auto", 0, 0, false, false, "", "brazilian_disc|galvez_beam|murray_beam|sphere_plate|packing", "Mesh generator; its parameters go in a [mesh.<generator>] table."},
    {"mesh", "time_limit", T::Real, "600.0", 0, 1e6, true, false, "s", nullptr, "With file: how long gmsh may take to read the mesh file, or to run and mesh a .geo script, before the run stops with an error. gmsh reads it in a child process that cannot start programs, write, remove or change files, or open sockets (a .geo is a program, and a case file is often someone else's)."},
    {"mesh", "cache", T::Bool, "true", 0, 0, false, false, "", nullptr, "Reuse a generated mesh when generator, parameters and gmsh version are unchanged (folder: $DSPDEM_MESH_CACHE, else ~/.cache/dspdem/meshes)."},
    {"physics", "gravity", T::Vec3, "[0.0, 0.0, 0.0]", -inf, inf, false, false, "m/s^2", nullptr, "Gravitational acceleration applied to every node."},
    {"contact", "enabled", T::Bool, "false", 0, 0, false, false, "", nullptr, "Contact between pieces (elements with a free face in different fragments or bodies) and with [[walls]] (README M3)."},
    {"contact", "step_fraction", T::Real, "0.5", 0, 1, true, false, "", nullptr, "Fraction of the contact springs' stability limit 2 sqrt(m / (4 kn)) that bounds the step. Impacts need the margin: two cubes colliding head-on gained 0.3 % of their energy at 0.5 and 5 % at 1. Contacts loaded slowly that stay closed (a specimen between plates) can use 1."},
    {"contact", "skin", T::Real, "auto", 0, inf, true, false, "m", nullptr, "Broad-phase skin: candidate pairs are kept until a node has moved half of it. Default: 0.2 x the mean size of the surface elements."},
    {"materials.<name>", "density", T::Real, nullptr, 0, inf, true, false, "kg/m^3", nullptr, "Mass density."},
    {"materials.<name>", "E", T::Real, nullptr, 0, inf, true, false, "Pa", nullptr, "Young's modulus."},
    {"materials.<name>", "nu", T::Real, nullptr, -1, 0.5, true, true, "", nullptr, "Poisson's ratio."},
    {"materials.<name>", "damping_alpha", T::Real, "0.0", 0, inf, false, false, "1/s", nullptr, "Mass-proportional Rayleigh coefficient (C = alpha M + beta K)."},
    {"materials.<name>", "damping_beta", T::Real, "0.0", 0, inf, false, false, "s", nullptr, "Stiffness-proportional Rayleigh coefficient."},
    {"materials.<name>", "damping_ratio", T::Real, "0.0", 0, 1, false, true, "", nullptr, "Damping ratio xi reached at damping_frequency; adds alpha = 2 xi w (mode mass) or beta = 2 xi / w (mode stiffness)."},
    {"materials.<name>", "damping_frequency", T::Real, "auto", 0, inf, true, false, "Hz", nullptr, "Frequency at which damping_ratio holds; required when damping_ratio > 0."},
    {"materials.<name>", "damping_mode", T::String, "\"mass\"", 0, 0, false, false, "", "mass|stiffness", "How damping_ratio is realised: mass-proportional (all modes decay at the same rate) or stiffness-proportional (ratio grows with frequency)."},
    {"materials.<name>", "tensile_strength", T::Real, "auto", 0, inf, true, false, "Pa", nullptr, "Joint tensile strength f_t (needed by fracturable bodies)."},
    {"materials.<name>", "fracture_energy_I", T::Real, "auto", 0, inf, true, false, "J/m^2", nullptr, "Mode-I fracture energy G_fI (area of the softening triangle)."},
    {"materials.<name>", "cohesion", T::Real, "auto", 0, inf, true, false, "Pa", nullptr, "Joint cohesion c (Mohr-Coulomb shear strength f_s = c - sigma_n tan(phi))."},
    {"materials.<name>", "friction_angle", T::Real, "auto", 0, 90, false, true, "deg", nullptr, "Joint friction angle phi (also the residual friction of broken joints in compression)."},
    {"materials.<name>", "fracture_energy_II", T::Real, "auto", 0, inf, true, false, "J/m^2", nullptr, "Mode-II fracture energy G_fII."},
    {"materials.<name>", "joint_penalty", T::Real, "100.0", 0, inf, true, false, "", nullptr, "Joint penalty factor p: k_n = k_s = p E / h, h the mean height of the two elements over the face. Larger: less added compliance (about 1.5/p on a tet block: 1.5 % at 100), smaller stable step (about 1/sqrt(p))."},
    {"materials.<name>", "mixed_mode", T::String, "\"energy\"", 0, 0, false, false, "", "energy|displacement", "Coupled law only: where a mixed-mode path breaks. energy: on the energies released per mode, G_I / G_fI + G_II / G_fII = 1 (Camanho & Davila 2002's power law, exponent 1), so a path's fracture energy always lies between G_fI and G_fII. displacement (the form before session 79): the eq. 6 ellipse on the displacements past the onset. They agree within 1 % up to 60 deg off the crack where w_GII = 2 G_fII / c exceeds w_GI = 2 G_fI / f_t (the paper's disc numbers); where it does not, the displacement form charges less: with the inter-element parameters c = 2 f_t, G_fII = G_fI 0.80-1.0 G_fI (the energy form exactly G_fI at any angle), with the sphere's c = 18 f_t 0.31 G_fI for a face 30 deg off its crack, below both modes' energies (the energy form: 1.2 G_fI). On the Brazilian disc and the Galvez beam the energy form moves the peak by +0.5 points of f_t and +1.2 % (src/joint/coupled_law.hpp)."},
    {"materials.<name>", "joint_quadrature", T::String, "\"gauss\"", 0, 0, false, false, "", "gauss|nodal", "Integration of the joint tractions (eq. 7): gauss (the paper's: 3 interior points per triangle, 2x2 per quadrilateral) or nodal (one point at each node of the face). Nodal removes the traction oscillations of Gauss integration under a stiff penalty (Schellekens & de Borst 1993): on a tet block in uniform tension the interior joint tractions scatter 0.36 % RMS instead of 1.5 %, and the Brazilian disc's splitting strength moves from -7.9 % to -3.1 % of f_t. Same cost."},
    {"materials.<name>", "joint_law", T::String, "\"paper\"", 0, 0, false, false, "", "paper|paper_residual|coupled|mode_I", "Cohesive law of the joints. paper: eqs. 3-6 as printed, normal and shear tractions soften independently and meet only in the mixed-mode break test (eq. 6); reproduces the paper, but a crack that must zigzag through faces inclined to it pays many times G_fI (the Brazilian disc on an unstructured mesh reads +160 % of f_t). paper_residual: the same, but the shear softens as the paper's text and Fig. 2(b) describe it: the cohesion softens over w_GII = 2 G_fII / c along the plastic slip and the friction -sigma_n tan(phi) stays, instead of the whole strength falling to zero before the residual friction starts (src/joint/residual_law.hpp); it differs from paper once a face passes its shear strength (elastic-plastic unloading, friction kept under compression) and where a compressed face breaks (its friction kept). coupled: one damage variable softens both tractions together, its break on the modes' energies (mixed_mode), onset by a quadratic traction criterion, cohesion degraded with the damage, no strength gain while a face opens, compression never damages (src/joint/coupled_law.hpp). mode_I: the paper's normal law only; the shear stays elastic until a joint breaks in opening (the paper's impact beam); give tensile_strength, fracture_energy_I and friction_angle, not cohesion or fracture_energy_II."},
    {"materials.<name>", "joint_kn", T::Real, "auto", 0, inf, true, false, "Pa/m", nullptr, "Normal penalty stiffness, overriding joint_penalty."},
    {"materials.<name>", "joint_ks", T::Real, "auto", 0, inf, true, false, "Pa/m", nullptr, "Shear penalty stiffness, overriding joint_penalty (default: k_n)."},
    {"materials.<name>", "contact_radius", T::Real, "auto", 0, inf, true, false, "m", nullptr, "Sphere radius r of the spheropolyhedra (the skeleton is the element shrunk by r); default: contact_radius_fraction x each element's inradius."},
    {"materials.<name>", "contact_radius_fraction", T::Real, "0.1", 0, 1, true, true, "", nullptr, "r as a fraction of each element's inradius (used when contact_radius is not given)."},
    {"materials.<name>", "contact_penalty", T::Real, "10.0", 0, inf, true, false, "", nullptr, "Contact normal stiffness factor: k_n = p E 2 rho per element (rho its inradius), two elements in series. Larger: less overlap, smaller stable step (about 1/sqrt(p))."},
    {"materials.<name>", "contact_kn", T::Real, "auto", 0, inf, true, false, "N/m", nullptr, "Normal contact stiffness per feature pair, overriding contact_penalty."},
    {"materials.<name>", "contact_kt_ratio", T::Real, "1.0", 0, inf, false, false, "", nullptr, "Tangential contact stiffness over the normal one."},
    {"materials.<name>", "friction", T::Real, "0.5", 0, inf, false, false, "", nullptr, "Coulomb friction coefficient of contacts (the smaller of the two materials is used)."},
    {"materials.<name>", "contact_restitution", T::Real, "0.8", 0.14, 1, false, false, "", nullptr, "Restitution of one contact (one feature pair: two node masses meeting head-on on the contact spring part with e times their approach speed; a body's own restitution also depends on its shape and modes). Sets contact_damping (0.8: 0.0744 of critical; src/contact/restitution.hpp); 1: elastic, energy-conserving contacts (the paper's law). At least 0.14 (e^-2 = 0.135 is critical damping). Give this or contact_damping, not both; two materials in contact take the lower restitution."},
    {"materials.<name>", "contact_damping", T::Real, "auto", 0, 1, false, false, "", nullptr, "Contact damping as a fraction of critical (normal, and tangential while sticking), instead of contact_restitution (0: elastic contacts); default: from contact_restitution. Two materials in contact take the larger."},
    {"bodies[]", "name", T::String, nullptr, 0, 0, false, false, "", nullptr, "Body name (unique)."},
    {"bodies[]", "groups", T::StringList, nullptr, 0, 0, false, false, "", nullptr, "Physical volume groups of the mesh that make up the body."},
    {"bodies[]", "material", T::String, nullptr, 0, 0, false, false, "", nullptr, "Name of a [materials.<name>] table."},
    {"bodies[]", "split_components", T::Bool, "false", 0, 0, false, false, "", nullptr, "Make every connected set of elements (sharing nodes) a body of its own, named <name>#<k> (e.g. one body per particle)."},
    {"bodies[]", "fracture", T::String, "\"none\"", 0, 0, false, false, "", "none|all|groups", "Cohesive joints on every interior face of the body (all), only between elements of fracture_groups (groups), or none."},
    {"bodies[]", "fracture_insertion", T::String, "\"intrinsic\"", 0, 0, false, false, "", "intrinsic|extrinsic", "When a face's joint starts to act. intrinsic: from the start, an elastic penalty spring until it softens (the paper's). extrinsic: the face stays closed (its sides one material: no added compliance) until the traction on it, from its two elements' stresses (time.insertion_stress), reaches the strength of its joint law; the joint then starts where that law's elastic branch ends, at that traction (continuous where the two elements carry the same stress; with insertion_stress = \"larger\" it starts from the more stressed element's). The penalty then acts only on opened joints (and on the faces time.insertion_front = \"cut\" opens with them), so it can be lower than an intrinsic joint's, for a step near the elements' own; it moves the strength (Brazilian disc, cut front: -7.9 % of the intrinsic peak at 1, -4.0 % at 2, +2.3 % at 3, +4.8 % at 5, +6.5 % at 10; cases/README.md); the step starts at the elements' and the contact's and falls as joints open; the price is that a face that opens and closes again gives back the skipped elastic energy f_t^2 / (2 k_n) per area (cases/README.md)."},
    {"bodies[]", "fracture_groups", T::StringList, "[]", 0, 0, false, false, "", nullptr, "Volume groups where cracks may form (fracture = \"groups\"): a face gets a joint when both its elements are in them."},
    {"bodies[]", "zone_groups", T::StringList, "[]", 0, 0, false, false, "", nullptr, "Volume groups of the body whose joints (faces with both elements in them) take the joint parameters of zone_material instead of the body's material: e.g. bearing zones under a load, where the macroscopic shear strength keeps facets from crushing while mode I can still open."},
    {"bodies[]", "zone_box_min", T::Vec3, "auto", -inf, inf, false, false, "m", nullptr, "With zone_box_max: elements of the body whose centroid (at the start) lies in this box (its faces included) join the joint zone, their joints with each other taking zone_material's parameters, as zone_groups' do. A zone without a volume group cut out along its edge: a cut is a mesh surface, a plane of faces along which a crack runs where none would on an unstructured mesh (the sphere's 50 mm contact cap came off along its cut, src/scenes/sphere_impact/REFERENCE.md)."},
    {"bodies[]", "zone_box_max", T::Vec3, "auto", -inf, inf, false, false, "m", nullptr, "The box's upper corner (see zone_box_min); above zone_box_min on every axis."},
    {"bodies[]", "zone_material", T::String, "\"\"", 0, 0, false, false, "", nullptr, "Material (a [materials.<name>] table with joint parameters) for the joints of zone_groups and the zone box; its elastic constants are not used (the elements keep the body's). The run's log says how many joints take it, and warns when none do (no two of the zone's fracturable elements share a face)."},
    {"bodies[]", "kinematics", T::String, "\"corotational\"", 0, 0, false, false, "", "corotational|small_strain|rigid", "Strain measure: corotational (objective, for large rotations) or small_strain (cheaper, small rotations only); rigid: the body moves as one free rigid motion (mass, centre and inertia of its lumped nodal masses), its elements carry mass and contact but no stress (a meshed impactor of any shape)."},
    {"boundary[]", "group", T::String, nullptr, 0, 0, false, false, "", nullptr, "Physical group (any dimension) whose nodes the condition acts on."},
    {"boundary[]", "type", T::String, nullptr, 0, 0, false, false, "", "fixed|velocity|force", "fixed: zero velocity; velocity: prescribed velocity; force: total force spread over the group (by area on surfaces, equally on nodes otherwise)."},
    {"boundary[]", "dofs", T::String, "\"xyz\"", 0, 0, false, false, "", nullptr, "Which components are constrained or loaded: any of x, y, z."},
    {"boundary[]", "value", T::Vec3, "[0.0, 0.0, 0.0]", -inf, inf, false, false, "m/s or N", nullptr, "Velocity (type velocity) or total force (type force); only the listed dofs are used."},
    {"boundary[]", "ramp", T::Real, "0.0", 0, inf, false, false, "s", nullptr, "Linear ramp from zero to value over this time (0 = applied at once)."},
    {"initial[]", "group", T::String, nullptr, 0, 0, false, false, "", nullptr, "Physical group whose nodes get the initial velocity."},
    {"initial[]", "velocity", T::Vec3, "[0.0, 0.0, 0.0]", -inf, inf, false, false, "m/s", nullptr, "Initial translational velocity."},
    {"initial[]", "angular_velocity", T::Vec3, "[0.0, 0.0, 0.0]", -inf, inf, false, false, "rad/s", nullptr, "Initial rigid spin about center: v += w x (x - center)."},
    {"initial[]", "center", T::Vec3, "[0.0, 0.0, 0.0]", -inf, inf, false, false, "m", nullptr, "Centre of the initial spin."},
    {"walls[]", "name", T::String, nullptr, 0, 0, false, false, "", nullptr, "Wall name (its contact force is written to series.csv as <name>_fx, _fy, _fz; a free wall's centre and velocity as <name>_x, _y, _z, _vx, _vy, _vz)."},
    {"walls[]", "type", T::String, nullptr, 0, 0, false, false, "", "plane|box|jaw|cylinder", "plane: the half-space behind a plane; box: an axis-aligned rigid box; jaw: the concave cylindrical face of a loading jaw (the ISRM Brazilian test's curved jaws, radius 1.5 R), the solid outside a cylinder about an axis; cylinder: a rigid roller or impactor (axis through point along axis, radius, length; its ends are rounded, a spherocylinder)."},
    {"walls[]", "point", T::Vec3, "[0.0, 0.0, 0.0]", -inf, inf, false, false, "m", nullptr, "A point of the plane, or the centre of the box."},
    {"walls[]", "normal", T::Vec3, "[0.0, 0.0, 1.0]", -inf, inf, false, false, "", nullptr, "Plane: normal pointing out of the solid side (normalised). Jaw: direction from the axis to the middle of the arc (normal to the axis)."},
    {"walls[]", "radius", T::Real, "auto", 0, inf, true, false, "m", nullptr, "Jaw: radius of its cylindrical face. Cylinder: its radius."},
    {"walls[]", "length", T::Real, "auto", 0, inf, true, false, "m", nullptr, "Cylinder: length of its axis segment, centred on point."},
    {"walls[]", "axis", T::Vec3, "[0.0, 0.0, 1.0]", -inf, inf, false, false, "", nullptr, "Jaw or cylinder: direction of the axis (point is a point of the axis)."},
    {"walls[]", "half_angle", T::Real, "30.0", 0, 90, true, true, "deg", nullptr, "Jaw: half opening angle of the arc, seen from the axis about normal."},
    {"walls[]", "half_size", T::Vec3, "[0.0, 0.0, 0.0]", 0, inf, false, false, "m", nullptr, "Box: half extents along x, y, z."},
    {"walls[]", "velocity", T::Vec3, "[0.0, 0.0, 0.0]", -inf, inf, false, false, "m/s", nullptr, "Prescribed velocity (free walls: the initial velocity)."},
    {"walls[]", "ramp", T::Real, "0.0", 0, inf, false, false, "s", nullptr, "Prescribed walls: linear ramp of the velocity from zero over this time."},
    {"walls[]", "free", T::Bool, "false", 0, 0, false, false, "", nullptr, "Boxes and cylinders: move as a free rigid body (mass from density, inertia of a solid box or cylinder, gravity applies)."},
    {"walls[]", "density", T::Real, "auto", 0, inf, true, false, "kg/m^3", nullptr, "Free boxes and cylinders: mass density (or give mass)."},
    {"walls[]", "mass", T::Real, "auto", 0, inf, true, false, "kg", nullptr, "Free boxes and cylinders: total mass, spread uniformly (instead of density)."},
    {"walls[]", "friction", T::Real, "auto", 0, inf, false, false, "", nullptr, "Friction coefficient against this wall (default: the element material's)."},
    {"walls[]", "kn", T::Real, "auto", 0, inf, true, false, "N/m", nullptr, "Wall stiffness in series with the element's (default: rigid, the element's k_n alone)."},
    {"time", "end", T::Real, nullptr, 0, inf, true, false, "s", nullptr, "Simulated end time."},
    {"time", "dt", T::Real, "auto", 0, inf, true, false, "s", nullptr, "Fixed time step; when absent, safety x the critical step."},
    {"time", "safety", T::Real, "0.9", 0, 1, true, false, "", nullptr, "Fraction of the critical step used when dt is absent."},
    {"time", "allow_unstable", T::Bool, "false", 0, 0, false, false, "", nullptr, "Accept a fixed dt above the critical step (for stability studies; the run's checks still stop a blow-up)."},
    {"time", "insertion_interval", T::Int, "1", 1, 1000000, false, false, "", nullptr, "Extrinsic insertion: check the closed faces every this many steps (a check is one pass over the elements and one over the closed faces; it takes the elements' stresses from that step's own force evaluation)."},
    {"time", "insertion_front", T::String, "\"cut\"", 0, 0, false, false, "", "tied|cut", "Extrinsic insertion: what opening a face does to its nodes. tied: a node's copies part only once opened faces cut all the way round it, so a face opened inside intact material cannot open until a whole ring of faces round one of its nodes has reached the strength by itself. cut: at each node of an opened face, the closed faces of the least cut between its two sides (each costing how far its traction stands from the onset) open too, as elastic joints carrying their current traction, so the opened face opens at once and the stress redistributes as round a softening intrinsic joint (Brazilian disc, joint penalty 2: tied +14.5 % of the intrinsic peak with the step fixed at every joint open's, cut -4.0 % with the step falling as joints open; cases/README.md)."},
    {"time", "insertion_stress", T::String, "\"larger\"", 0, 0, false, false, "", "larger|mean", "Extrinsic insertion: the stress that gives a closed face its traction. larger: each of its two elements' own, whichever is nearer the onset; mean: their mean, which smooths a stress peak over two elements and opens faces late (Brazilian disc: splitting strength +21.6 % of f_t with mean, +1.7 % with larger, -3.5 % with intrinsic joints)."},
    {"time", "max_steps", T::Int, "0", 0, inf, false, false, "", nullptr, "Stop after this many steps (0 = no limit)."},
    {"time", "stop_series", T::String, "auto", 0, 0, false, false, "", nullptr, "End the run early once this series.csv column (a wall force such as plate_top_fy, a monitor, or kinetic: the kinetic energy) has passed its peak and fallen below stop_fraction of it; a last frame is written there. For tests that are over when the specimen breaks, and heaps that have come to rest."},
    {"time", "stop_fraction", T::Real, "0.3", 0, 1, true, true, "", nullptr, "With stop_series: the fraction of the peak |value| below which the run ends."},
    {"time", "stop_delay", T::Real, "0.0", 0, inf, false, false, "s", nullptr, "With stop_series: run on this long after the drop before ending (the pieces of a specimen that has just lost its load may still be separating)."},
    {"time", "stop_min_peak", T::Real, "0.0", 0, inf, false, false, "", nullptr, "With stop_series: the peak |value| must first reach this (keeps the first contact's ringing from ending the run)."},
    {"time", "stop_reach", T::Real, "0.0", 0, inf, false, false, "", nullptr, "With stop_series: also end the run once |value| has reached this (after stop_delay; a last frame is written there), for runs wanted only up to a load; 0: no such end. The Brazilian disc's stress check stops at the scene's profile load."},
    {"output", "frame_interval", T::Real, "auto", 0, inf, true, false, "s", nullptr, "Simulated time between VTU frames; default end/20."},
    {"output", "series_interval", T::Real, "auto", 0, inf, true, false, "s", nullptr, "Simulated time between rows of series.csv; default frame_interval/10."},
    {"output", "fields", T::StringList, "[\"displacement\", \"velocity\", \"stress\", \"von_mises\", \"max_principal\", \"body\", \"material\"]", 0, 0, false, false, "", "displacement|velocity|stress|von_mises|max_principal|body|material|element", "Fields written to each frame (element: each cell's gmsh element tag)."},
    {"output", "compress", T::Bool, "true", 0, 0, false, false, "", nullptr, "zlib-compress the VTU data arrays."},
    {"monitors[]", "name", T::String, nullptr, 0, 0, false, false, "", nullptr, "Column name in series.csv (unique)."},
    {"monitors[]", "type", T::String, nullptr, 0, 0, false, false, "", "reaction|displacement|displacement_difference|max_displacement|velocity|momentum|broken_joints|crack_area", "reaction: sum of support reactions on the group's constrained dofs [N]; displacement/velocity: mean over the group [m, m/s]; displacement_difference: mean of group2 minus mean of group [m]; max_displacement: largest over the group [m]; momentum: sum of nodal mass x velocity over the group [kg m/s] (for momentum checks: add the free walls' mass x velocity); broken_joints: failed joints in a region (box_min, box_max; default all) [count]; crack_area: their area at the start [m^2]. The last two tell where a body breaks over time, e.g. how much of the breaking is crushing under a contact (series.csv's broken_joints and crack_area count all joints)."},
    {"monitors[]", "group", T::String, "auto", 0, 0, false, false, "", nullptr, "Physical group (default: all nodes, for max_displacement and momentum only; broken_joints and crack_area take a box instead)."},
    {"monitors[]", "group2", T::String, "auto", 0, 0, false, false, "", nullptr, "Second group for displacement_difference."},
    {"monitors[]", "box_min", T::Vec3, "auto", -inf, inf, false, false, "m", nullptr, "broken_joints, crack_area: with box_max, count only the joints whose face centroid at the start lies in this box (its faces included); default: every joint."},
    {"monitors[]", "box_max", T::Vec3, "auto", -inf, inf, false, false, "m", nullptr, "The box's upper corner (see box_min); above box_min on every axis."},
    {"monitors[]", "component", T::String, "\"magnitude\"", 0, 0, false, false, "", "x|y|z|magnitude", "Component recorded (not for broken_joints and crack_area, which are counts)."},
    {"render", "views", T::StringList, "[\"stress\", \"fragments\"]", 0, 0, false, false, "", "stress|fragments|cracks", "Views drawn by dspdem render: stress field, fragments (one colour each), cracks (broken joints over a translucent body)."},
    {"render", "field", T::String, "\"von_mises\"", 0, 0, false, false, "", "von_mises|max_principal|sigma_xx|sigma_yy|sigma_zz|sigma_xy|sigma_yz|sigma_xz|displacement", "Field of the stress view."},
    {"render", "magnify", T::Real, "1.0", 0, inf, true, false, "", nullptr, "Displacement magnification for drawing (the paper shows x100)."},
    {"render", "range_min", T::Real, "auto", -inf, inf, false, false, "Pa", nullptr, "Lower end of the colour range; default: 0.5th percentile over all frames (0 for von Mises)."},
    {"render", "range_max", T::Real, "auto", -inf, inf, false, false, "Pa", nullptr, "Upper end of the colour range; default: 99.5th percentile over all frames."},
    {"render", "camera", T::String, "\"iso\"", 0, 0, false, false, "", "front|back|top|side|iso", "Camera preset (parallel projection, framed on the first frame)."},
    {"render", "fit", T::String, "\"diagonal\"", 0, 0, false, false, "", "diagonal|box", "How the camera frames the first frame: diagonal, its bounding box's diagonal across the image's shorter side, for every camera (pieces flying off stay in view); box, for front, back, top and side, the face of the box seen fills the image with a 30 % margin (a long beam in a wide image)."},
    {"render", "cut", T::String, "\"none\"", 0, 0, false, false, "", "none|x|y|z", "Cut the bodies at the mid-plane normal to this axis and show the half below it."},
    {"render", "width", T::Int, "1280", 16, 8192, false, false, "px", nullptr, "Image width."},
    {"render", "height", T::Int, "720", 16, 8192, false, false, "px", nullptr, "Image height."},
    {"render", "background", T::Vec3, "[1.0, 1.0, 1.0]", 0, 1, false, false, "", nullptr, "Background colour (RGB, 0-1)."},
    {"render", "edges", T::Bool, "false", 0, 0, false, false, "", nullptr, "Draw the element edges over the stress and fragments views."},
    {"render", "animation", T::Bool, "true", 0, 0, false, false, "", nullptr, "Write an animation per view (.ogv; .mp4 and .gif when ffmpeg is installed)."},
    {"render", "fps", T::Int, "10", 1, 120, false, false, "1/s", nullptr, "Animation frame rate."},
    {"render", "plots", T::StringList, "[]", 0, 0, false, false, "", nullptr, "Extra plots of series.csv, each \"x:y1,y2\" (e.g. \"cmod:load\"); energies and monitors against time are always plotted."},
    {"render", "plot_reference", T::String, "\"\"", 0, 0, false, false, "", nullptr, "CSV with the same column names, drawn dashed over the extra plots (e.g. a test curve)."},
    {"checks", "contact_overlap_limit", T::Real, "1.0", 0, 2, false, true, "", nullptr, "Stop, naming the step, time and both elements, when a contact's overlap exceeds this fraction of the two contact radii r_a + r_b. Beyond 1 the contact skeletons cross: a vertex inside the other piece's skeleton (measured up to 2) or through a wall; a crossing of two edges is not measured (their distance stays >= 0), so it is not caught. 0: no check."},
    {"checks", "energy_blowup_factor", T::Real, "10.0", 1, inf, true, false, "", nullptr, "Stop when kinetic + internal energy exceeds this factor times (initial energy + work done on the body + a floor)."},
    {"checks", "energy_balance_warn", T::Real, "0.01", 0, inf, false, false, "", nullptr, "Warn once, naming the step, time and energy terms, when the energy ledger error (the balance's size over its largest term: series.csv's balance_error) has exceeded this on two series rows in a row (or on the last), at the first of them; the run goes on. 0: no warning."},
  };
  return k;
}
}  // namespace
// clang-format on

// The general keys, with each mesh generator's own keys (declared in meshing/<name>.cpp)
// after the [mesh] ones.
const std::vector<Key>& keys() {
  static const std::vector<Key> k = [] {
    std::vector<Key> out;
    const auto& g = general_keys();
    std::size_t i = 0;
    while (i < g.size() && std::string(g[i].section) != "mesh") out.push_back(g[i++]);
    while (i < g.size() && std::string(g[i].section) == "mesh") out.push_back(g[i++]);
    for (const auto& gen : meshing::registry())
      for (const auto& key : gen.keys()) out.push_back(key);
    out.insert(out.end(), g.begin() + static_cast<std::ptrdiff_t>(i), g.end());
    return out;
  }();
  return k;
}

// clang-format on

const char* type_name(Type t) {
  switch (t) {
    case Type::Real:
      return "number";
    case Type::Int:
      return "integer";
    case Type::Bool:
      return "boolean";
    case Type::String:
      return "string";
    case Type::Vec3:
      return "[x, y, z]";
    case Type::StringList:
      return "list of strings";
  }
  return "?";
}

std::string range_text(const Key& k) {
  if (k.type != Type::Real && k.type != Type::Int) return k.choices ? std::string(k.choices) : "";
  const bool has_lo = k.lo > -inf, has_hi = k.hi < inf;
  if (has_lo && has_hi) return fmt::format("{}{}, {}{}", k.lo_open ? "(" : "[", k.lo, k.hi, k.hi_open ? ")" : "]");
  if (has_lo) return fmt::format("{} {}", k.lo_open ? ">" : ">=", k.lo);
  if (has_hi) return fmt::format("{} {}", k.hi_open ? "<" : "<=", k.hi);
  return "";
}

}  // namespace dspdem::schema
