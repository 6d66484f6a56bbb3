// Mesh reading (read_gmsh): broken .msh files are refused by line before gmsh sees them, and
// one unreadable file does not break the reads after it. Regression tests for the defects
// the fuzz test (tests/robustness/test_fuzz_inputs.cpp) found.
#include <gmsh.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "mesh/geo_check.hpp"
#include "mesh/gmsh_reader.hpp"

using namespace dspdem;

namespace {
namespace fs = std::filesystem;

// One tet4 in the volume group "solid" and its bottom face in the surface group "bottom".
const char* kTetV2 = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
2 1 "bottom"
3 2 "solid"
$EndPhysicalNames
$Nodes
4
1 0 0 0
2 1 0 0
3 0 1 0
4 0 0 1
$EndNodes
$Elements
2
1 2 2 1 1 1 3 2
2 4 2 2 1 1 2 3 4
$EndElements
)";

// The same tet in format 4.0 (gmsh 4.0's: entity tags before dimensions, a node per line).
const char* kTetV40 = R"($MeshFormat
4 0 8
$EndMeshFormat
$PhysicalNames
2
2 1 "bottom"
3 2 "solid"
$EndPhysicalNames
$Entities
0 0 1 1
1 0 0 0 1 1 0 1 1 0
1 0 0 0 1 1 1 1 2 1 1
$EndEntities
$Nodes
2 4
1 2 0 3
1 0 0 0
2 1 0 0
3 0 1 0
1 3 0 1
4 0 0 1
$EndNodes
$Elements
2 2
1 2 2 1
1 1 3 2
1 3 4 1
2 1 2 3 4
$EndElements
)";

std::string write_file(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "dspdem_mesh_reader";
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  return s.replace(p, from.size(), to);
}

// Expects read_gmsh to throw Error naming the file and every fragment.
void expect_error(const std::string& name, const std::string& text, const std::vector<std::string>& fragments) {
  const std::string path = write_file(name, text);
  try {
    read_gmsh(path);
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << "file not named: " << msg;
    for (const auto& f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << "'" << f << "' not in: " << msg;
  }
}

void expect_tet(const Mesh& m) {
  EXPECT_EQ(m.n_nodes(), 4);
  EXPECT_EQ(m.n_elements(), 1);
  ASSERT_NE(m.find_group("solid"), nullptr);
  ASSERT_NE(m.find_group("bottom"), nullptr);
  EXPECT_EQ(m.find_group("bottom")->tri.size(), 3u);
}
}  // namespace

TEST(MeshReader, ReadsFormats2And40) {
  expect_tet(read_gmsh(write_file("tet_v2.msh", kTetV2)));
  expect_tet(read_gmsh(write_file("tet_v40.msh", kTetV40)));
}

TEST(MeshReader, ElementWithAMissingNodeIsRefusedByLine) {
  // Fuzz: an element naming a node that $Nodes does not list crashed the process (SIGSEGV
  // in gmsh's GModel::_associateEntityWithMeshVertices).
  expect_error("dangling.msh", replace(kTetV2, "2 4 2 2 1 1 2 3 4", "2 4 2 2 1 1 2 3 5"),
               {"line 19", "element 2 refers to node 5"});
  expect_error("dangling_v40.msh", replace(kTetV40, "2 1 2 3 4", "2 1 2 3 9"),
               {"line 28", "element 2 refers to node 9"});
}

TEST(MeshReader, BrokenStructureIsNamedByLine) {
  // Fuzz: these reached gmsh, whose refusal named no line ("Error loading '<file>'").
  expect_error("count.msh", replace(kTetV2, "$Nodes\n4\n", "$Nodes\n5\n"),
               {"line 15", "$Nodes declares 5 nodes but lists 4"});
  expect_error("nan.msh", replace(kTetV2, "3 0 1 0", "3 0 nan 0"), {"line 13", "node coordinate", "nan"});
  expect_error("section.msh", replace(kTetV2, "$EndNodes", "$EndNode"), {"line 15", "expected $EndNodes"});
  expect_error("type.msh", replace(kTetV2, "2 4 2 2 1 1 2 3 4", "2 99 2 2 1 1 2 3 4"),
               {"line 19", "element type", "'99'"});
  expect_error("garbage.msh", std::string(kTetV2) + "$NodeData\n1\n$EndNodeData\n", {"line 21", "$NodeData"});
  // gmsh runs a file that does not start with $MeshFormat as a .geo script.
  expect_error("blank_first.msh", std::string(1, '\n').append(kTetV2), {"line 1", "must start with $MeshFormat"});
  // A text file marked binary (a flipped bit in the file type) would be read as bytes.
  expect_error("binary.msh", replace(kTetV2, "2.2 0 8", "2.2 1 8"), {"line 3", "binary"});
  expect_error("surface_only.msh", replace(kTetV2, "2\n1 2 2 1 1 1 3 2\n2 4 2 2 1 1 2 3 4\n", "1\n1 2 2 1 1 1 3 2\n"),
               {"line 16", "no volume (3D) elements"});
}

TEST(MeshReader, AnUnreadableFileDoesNotBreakLaterReads) {
  // A gmsh error inside its file reader left the reader's lock set: every later read in the
  // process got an empty model ("no volume entities"), even of a good file.
  expect_error("bad.geo", "Point(1) = {0, 0, 0, ;\n", {"line 1", "syntax error"});
  expect_tet(read_gmsh(write_file("after_bad.msh", kTetV2)));
}

// Expects check_geo_script to refuse `text` (written as `name`) naming every fragment. The
// refusals are checked without gmsh: were one to fail, gmsh would run the command in the test
// (Exit ends the process with status 0, which ctest counts as a pass; Sleep hangs it).
void expect_geo_refused(const std::string& name, const std::string& text, const std::vector<std::string>& fragments) {
  const std::string path = write_file(name, text);
  try {
    check_geo_script(path, text);
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const Error& e) {
    const std::string msg = e.what();
    for (const auto& f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << "'" << f << "' not in: " << msg;
  }
}

// A .geo's commands that act outside the model are refused by line before gmsh runs anything:
// a case file is often someone else's, run in batch on a shared server. The script is read as
// gmsh 4.8's lexer reads it, or a string or comment could hide a command from the check.
TEST(MeshReader, GeoCommandsThatActOutsideTheModelAreRefusedByLine) {
  const fs::path marker = fs::temp_directory_path() / "dspdem_mesh_reader" / "system_call_ran";
  fs::remove(marker);
  const std::string box = "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\nMesh.MeshSizeMax = 0.6;\n";
  const std::string touch = "\"touch " + marker.string() + "\"";
  // Through the reader: refused before gmsh opens the file, and the command did not run.
  expect_error("system_call.geo", box + "SystemCall " + touch + ";\n", {"line 4", "SystemCall", "does not run it"});
  write_file("opt_case.geo", box);
  write_file("opt_case.geo.opt", "SystemCall " + touch + ";\n");  // gmsh runs <file>.opt beside it
  expect_error("opt_case.geo", box, {"opt_case.geo.opt", "line 1", "SystemCall"});
  fs::remove(fs::temp_directory_path() / "dspdem_mesh_reader" / "opt_case.geo.opt");
  // ... and <file>.opt.opt beside that, and on (a third review's finding).
  write_file("opt_case.geo.opt", "// options\n");
  write_file("opt_case.geo.opt.opt", "SystemCall " + touch + ";\n");
  expect_error("opt_case.geo", box, {"opt_case.geo.opt.opt", "line 1", "SystemCall"});
  fs::remove(fs::temp_directory_path() / "dspdem_mesh_reader" / "opt_case.geo.opt");
  fs::remove(fs::temp_directory_path() / "dspdem_mesh_reader" / "opt_case.geo.opt.opt");
  EXPECT_FALSE(fs::exists(marker)) << "a script's command ran";
  // Ways two reviews found past earlier versions of the check (each ran its command then):
  // gmsh has no escapes and takes single quotes; a NUL ends its // comment; S2N names a
  // command from a string; System is SystemCall's alias; an Include of any extension is parsed
  // as a script; a false If skips to an EndIf inside a string; a For's body is read again from
  // the line after its header; an option's category indexed or on the next line.
  expect_geo_refused("backslash.geo", box + "s = \"\\\"; SystemCall " + touch + "; // \"\n", {"line 4", "SystemCall"});
  expect_geo_refused("single_quote.geo", box + "x = '\"'; SystemCall " + touch + "; y = '\"';\n",
                     {"line 4", "SystemCall"});
  expect_geo_refused("nul.geo", box + "// note" + std::string(1, '\0') + "SystemCall " + touch + ";\n",
                     {"line 4", "NUL byte"});
  expect_geo_refused("s2n.geo", box + "S2N[StrCat(\"System\", \"Call\")] " + touch + ";\n", {"line 4", "S2N"});
  write_file("evil.stl", "SystemCall " + touch + ";\n");
  expect_geo_refused("include_stl.geo", box + "Include \"evil.stl\";\n",
                     {"line 4", "evil.stl", "line 1", "SystemCall"});
  write_file("evil.Step", "SystemCall " + touch + ";\n");  // gmsh knows .step, .STEP, .stp, .STP only
  expect_geo_refused("merge_spelt.geo", box + "Merge \"evil.Step\";\n", {"line 4", "evil.Step", "spelt"});
  expect_geo_refused("if_skip.geo", box + "If (0)\nx = \"EndIf Exit; y = '\"'; // '\nEndIf\n",
                     {"line 5", "'Exit' in a string or a comment"});
  expect_geo_refused("for_header.geo", box + "For i In {1:2} x = \"\nSystemCall 'true'; // \";\nEndFor\n",
                     {"line 5", "'SystemCall' in a string or a comment"});
  expect_geo_refused("hidden_include.geo", box + "If (0)\nx = \"EndIf Include 'x.geo'; // \";\nEndIf\n",
                     {"line 5", "'Include' in a string or a comment"});
  expect_geo_refused("general_index.geo", box + "General[0].AbortOnError = 4;\n", {"line 4", "General"});
  // A third review's: Delete Options turned AbortOnError off, and gmsh cuts a string at 1023
  // characters and reads the rest as code (there a Printf > 'file' the check had read as a string).
  for (const char* del : {"Options", "All", "Model"})
    expect_geo_refused("delete.geo", box + "Delete " + del + ";\n", {"line 4", std::string("Delete ") + del});
  // A fourth review's: gmsh takes a backslash for a folder separator and "c:" for a drive, so it
  // read another file than the one the check had read.
  expect_geo_refused("backslash_include.geo", box + "Include \"sub\\inner.geo\";\n", {"line 4", "a backslash"});
  expect_geo_refused("drive_merge.geo", box + "Merge \"c:/part.stl\";\n", {"line 4", "drive letter"});
  expect_geo_refused("top\\case.geo", box, {"a backslash"});
  expect_geo_refused("hidden_delete.geo", box + "If (0)\nx = \"EndIf Delete Options; // \";\nEndIf\n",
                     {"line 5", "'Delete' in a string or a comment"});
  expect_geo_refused("long_string.geo", box + "x = \"" + std::string(1024, 'a') + "\";\n",
                     {"line 4", "1024 characters", "at most 1023"});
  EXPECT_NO_THROW(
      check_geo_script("delete_ok.geo", box + "Delete Physicals;\nx = \"" + std::string(1023, 'a') + "\";\n"));
  expect_geo_refused("general_line.geo", box + "General\n.AbortOnError = 4;\n", {"line 4", "General"});
  for (const char* cmd :
       {"System \"true\";", "NonBlockingSystemCall \"true\";", "Exit;", "Sleep 1e9;", "CreateDir \"made\";",
        "Save \"copy.msh\";", "Print \"view.png\";", "OnelabRun(\"x\", \"true\");", "MergeWithBoundingBox \"a.geo\";",
        "Plugin(Bubbles).OutputFile = \"victim\";", "General.AbortOnError = 4;", "Solver.Executable0 = \"sh\";"})
    expect_geo_refused("refused.geo", box + "  " + cmd + "\n", {"line 4", std::string(cmd).substr(0, 4)});
  EXPECT_FALSE(fs::exists(marker)) << "a script's command ran";
  // Printf writes into a file only past its parenthesis: "a > b" inside is a comparison.
  expect_geo_refused("printf.geo", box + "Printf(\"%g\", 2 > 1) >> \"out.txt\";\n", {"line 4", "Printf into a file"});
  expect_geo_refused("printf_quote.geo", box + "Printf(')') > \"out.txt\";\n", {"line 4", "Printf into a file"});
  // Include and Merge: a name the script makes is not checked, so it is refused.
  expect_geo_refused("include_made.geo", box + "Include StrCat(\"a\", \".geo\");\n", {"line 4", "in quotes"});
  write_file("inner_bad.geo", "// an included script\n\nExit;\n");
  expect_geo_refused("include_bad.geo", box + "Include \"inner_bad.geo\";\n", {"inner_bad.geo", "line 3", "Exit"});
  expect_geo_refused("merge_py.geo", box + "Merge \"solver.py\";\n", {"line 4", "solver.py"});
  expect_geo_refused("include_self.geo", box + "Include \"include_self.geo\";\n", {"nested more than 16"});
  expect_geo_refused("open_comment.geo", box + "/* never closed\n", {"line 4", "never closed"});
  expect_geo_refused("open_string.geo", box + "s = 'never closed;\n", {"line 4", "never closed"});
  write_file("part.stl.opt", "Exit;\n");
  write_file("part.stl", "solid x\nendsolid x\n");
  expect_geo_refused("merge_opt.geo", box + "Merge \"part.stl\";\n", {"part.stl.opt", "Exit"});
  fs::remove(fs::temp_directory_path() / "dspdem_mesh_reader" / "part.stl.opt");

  // What a meshing script uses is read: comments and strings, option categories named like a
  // command (Print.Width), Printf to the terminal, an included script, and a merged surface
  // mesh (no volume elements: the script builds its volume from it) or CAD file.
  write_file("inner_ok.geo", "Physical Volume('solid') = {1};\n");
  const Mesh m = read_gmsh(write_file("fine.geo", box + "// the box, meshed coarsely\n"
                                                        "/* a comment */ Printf(\"meshed: %g\", 1);\n"
                                                        "Print.Width = 800;\nInclude \"inner_ok.geo\";\n"));
  EXPECT_GT(m.n_elements(), 0);
  EXPECT_NE(m.find_group("solid"), nullptr);
  const std::string surface = replace(kTetV2, "2\n1 2 2 1 1 1 3 2\n2 4 2 2 1 1 2 3 4\n", "1\n1 2 2 1 1 1 3 2\n");
  write_file("surface.msh", surface);
  write_file("part.STEP", "not read by the check");
  const std::string merges = "Merge \"surface.msh\";\nMerge 'part.STEP';\nMerge \"part.stl\";\n";
  EXPECT_NO_THROW(check_geo_script(write_file("merges.geo", merges), merges));
}

namespace {
// Expects read_gmsh_unchecked (gmsh in the sandbox, without the checks that would refuse the
// script first) to throw Error naming the file and one of `any`.
void expect_stopped(const std::string& name, const std::string& text, const std::vector<std::string>& any,
                    double time_limit = 60) {
  const std::string path = write_file(name, text);
  try {
    read_gmsh_unchecked(path, "", time_limit);
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << "file not named: " << msg;
    bool named = false;
    for (const auto& f : any) named = named || msg.find(f) != std::string::npos;
    EXPECT_TRUE(named) << msg;
  }
}
}  // namespace

// The second line of defence, behind the checks of the text above: gmsh runs the script in a
// child process that cannot start programs, write, remove or make files, and that is stopped
// at [mesh] time_limit. Each script here gets past no check (none is made): what it would do
// is stopped by the sandbox, and leaves no trace.
TEST(MeshReader, AGeoScriptRunsWhereItCannotActOutsideTheModel) {
  const fs::path dir = fs::temp_directory_path() / "dspdem_mesh_reader";
  const fs::path marker = dir / "sandboxed_call_ran", saved = dir / "sandboxed_save.msh", made = dir / "sandboxed_dir";
  fs::remove(marker);
  fs::remove(saved);
  fs::remove(made);
  const std::string box = "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\nMesh.MeshSizeMax = 0.6;\n";
  const std::string stopped = "gmsh was stopped at";
  expect_stopped("sandboxed_call.geo", box + "SystemCall \"touch " + marker.string() + "\";\n", {stopped});
  expect_stopped("sandboxed_save.geo", box + "Mesh 3;\nSave \"" + saved.string() + "\";\n",
                 {stopped + " the system call openat"});
  expect_stopped("sandboxed_dir.geo", box + "CreateDir \"" + made.string() + "\";\n",
                 {stopped + " the system call mkdir"});
  // Exit ends the child (and its exit handlers may try more): no mesh, and the run goes on.
  expect_stopped("sandboxed_exit.geo", box + "Exit;\n", {"ended before it had read the mesh", stopped});
  expect_stopped("sandboxed_sleep.geo", box + "Sleep 100;\n",
                 {"gmsh did not finish within 1 s and was stopped ([mesh] time_limit"}, 1.0);
  EXPECT_FALSE(fs::exists(marker));
  EXPECT_FALSE(fs::exists(saved));
  EXPECT_FALSE(fs::exists(made));
  // This process's gmsh is as it was: a good file reads.
  expect_tet(read_gmsh(write_file("after_sandboxed.msh", kTetV2)));
}

namespace {
// Same nodes, elements and groups in the same order; coordinates within `rel` of each other
// (0: the same doubles).
void expect_same_mesh(const Mesh& a, const Mesh& b, double rel) {
  EXPECT_EQ(a.node_tag, b.node_tag);
  ASSERT_EQ(a.x.size(), b.x.size());
  for (std::size_t i = 0; i < a.x.size(); ++i)
    ASSERT_LE(std::abs(a.x[i] - b.x[i]), rel * std::abs(a.x[i])) << "coordinate " << i;
  ASSERT_EQ(a.blocks.size(), b.blocks.size());
  for (std::size_t k = 0; k < a.blocks.size(); ++k) {
    EXPECT_EQ(a.blocks[k].conn, b.blocks[k].conn);
    EXPECT_EQ(a.blocks[k].tag, b.blocks[k].tag);
  }
  ASSERT_EQ(a.groups.size(), b.groups.size());
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    EXPECT_EQ(a.groups[g].name, b.groups[g].name);
    EXPECT_EQ(a.groups[g].dim, b.groups[g].dim);
    EXPECT_EQ(a.groups[g].nodes, b.groups[g].nodes);
    EXPECT_EQ(a.groups[g].elements, b.groups[g].elements);
    EXPECT_EQ(a.groups[g].tri, b.groups[g].tri);
    EXPECT_EQ(a.groups[g].quad, b.groups[g].quad);
  }
}
}  // namespace

// The mesh comes from the child as a dump of gmsh's model and is loaded into this process's
// gmsh again: it is the mesh gmsh makes of the script in this process (the same doubles), and
// the .msh written from it reads back as the same mesh (gmsh writes coordinates with 16
// digits: within 1e-15 of them).
TEST(MeshReader, AMeshReadInTheSandboxIsTheMeshGmshMakesAndWrites) {
  const fs::path dir = fs::temp_directory_path() / "dspdem_mesh_reader";
  const std::string geo = std::string(DSPDEM_SOURCE_DIR) + "/tests/data/tension_block.geo";
  const std::string saved = (dir / "round_trip.msh").string();
  const Mesh m = read_gmsh(geo, saved);
  ASSERT_GT(m.n_elements(), 100);
  ASSERT_EQ(m.groups.size(), 5u);
  EXPECT_GT(m.find_group("left")->tri.size(), 0u);
  Mesh here;
  {
    GmshSession session;  // a trusted script of the tests, run in this process
    gmsh::open(geo);
    gmsh::model::mesh::generate(3);
    here = mesh_from_gmsh_model(geo);
  }
  expect_same_mesh(here, m, 0);
  expect_same_mesh(m, read_gmsh(saved), 1e-15);
}

// Groups of every dimension, from a gmsh 4.1 file: a point group whose point has its node but
// no point element (gmsh lists the point's own node for it; a review found the conversion
// from the child's arrays had dropped it), a curve, a surface and the volume.
constexpr const char* kGroupsV41 = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
4
0 1 "apex"
1 2 "edge"
2 3 "bottom"
3 4 "solid"
$EndPhysicalNames
$Entities
1 1 1 1
4 0 0 1 1 1
1 0 0 0 1 0 0 1 2 0
1 0 0 0 1 1 0 1 3 0
1 0 0 0 1 1 1 1 4 0
$EndEntities
$Nodes
4 4 1 4
0 4 0 1
4
0 0 1
1 1 0 2
1
2
0 0 0
1 0 0
2 1 0 1
3
0 1 0
3 1 0 0
$EndNodes
$Elements
3 3 1 3
1 1 1 1
2 1 2
2 1 2 1
3 1 3 2
3 1 4 1
1 1 2 3 4
$EndElements
)";

TEST(MeshReader, GroupsOfEveryDimensionListTheirNodes) {
  const Mesh m = read_gmsh(write_file("groups_v41.msh", kGroupsV41));
  ASSERT_EQ(m.n_nodes(), 4);
  ASSERT_EQ(m.n_elements(), 1);
  // Nodes numbered as the tetrahedron lists them: tags 1 2 3 4 are 0 1 2 3.
  EXPECT_EQ(m.node_tag, (std::vector<std::size_t>{1, 2, 3, 4}));
  ASSERT_NE(m.find_group("apex"), nullptr);
  EXPECT_EQ(m.find_group("apex")->dim, 0);
  EXPECT_EQ(m.find_group("apex")->nodes, (std::vector<Index>{3}));
  EXPECT_EQ(m.find_group("edge")->nodes, (std::vector<Index>{0, 1}));
  EXPECT_EQ(m.find_group("bottom")->nodes, (std::vector<Index>{0, 1, 2}));
  EXPECT_EQ(m.find_group("bottom")->tri, (std::vector<Index>{0, 2, 1}));
  EXPECT_EQ(m.find_group("solid")->nodes, (std::vector<Index>{0, 1, 2, 3}));
  EXPECT_EQ(m.find_group("solid")->elements[0], (std::vector<Index>{0}));
}

// What gmsh reads otherwise than its name says, or what the check itself could not get
// through (a probe's findings): each refused with the file named, none run.
TEST(MeshReader, AFileIsCheckedAsWhatGmshReadsItAs) {
  // gmsh reads a mesh by its first line, whatever the name: a .geo holding a mesh (here with
  // a node listed twice, which the .msh check refuses) is refused; a .msh that does not start
  // as a mesh would run as a script, and is refused by the .msh check.
  const std::string twice = replace(kTetV2, "4 0 0 1\n", "3 0 1 100\n");
  expect_error("mesh_as.geo", twice, {"holds a mesh", "name it .msh"});
  expect_error("script_as.msh", " " + std::string(kTetV2), {"line 1", "must start with $MeshFormat"});
  // Merged, a .geo holding a mesh is checked as the mesh it is.
  write_file("merged_mesh.geo", twice);
  expect_error("merges_mesh.geo", "Merge \"merged_mesh.geo\";\n", {"merged_mesh.geo", "listed twice"});
  // A post-processing view, as the case's file, merged, or as a .opt beside a file: refused,
  // the view's file named once, where the case's script merges it.
  expect_geo_refused("view_as.geo", "$View\n", {"holds a post-processing view", "name it .msh"});
  write_file("merged_view.geo", "$PostFormat\n1.4 0 8\n$EndPostFormat\n");
  expect_error("merges_view.geo", "Merge \"merged_view.geo\";\n",
               {"line 1: Merge \"merged_view.geo\": mesh file '", "merged_view.geo': a post-processing view"});
  write_file("view_opt.geo.opt", "$View\n");
  expect_error("view_opt.geo", "Point(1) = {0, 0, 0};\n", {"view_opt.geo.opt': a post-processing view"});
  // Threaded meshing: another mesh each run, and OpenMP's pool is not safe in the sandbox.
  expect_geo_refused("threads.geo", "Mesh.MaxNumThreads3D = 2;\n", {"line 1", "MaxNumThreads3D"});
  expect_geo_refused("threads_hidden.geo", "// Mesh.MaxNumThreads2D = 4;\n", {"MaxNumThreads2D"});
  // A name too long for the file system: the file's error, not dspdem's failure.
  expect_error("long_include.geo", "Include \"" + std::string(300, 'a') + ".geo\";\n", {"name too long"});
}

// Each included file is checked once: a chain of files each including the next ten times was
// read 10^15 times before gmsh ever ran (a probe's), outside the time limit. Were each read
// again, this test would not end before its time-out.
TEST(MeshReader, AFileIncludedManyTimesIsCheckedOnce) {
  std::string last = "Point(1) = {0, 0, 0};\n";
  write_file("chain_12.geo", last);
  for (int k = 11; k >= 0; --k) {
    std::string text;
    for (int i = 0; i < 10; ++i) text += "Include \"chain_" + std::to_string(k + 1) + ".geo\";\n";
    write_file("chain_" + std::to_string(k) + ".geo", text);
  }
  const std::string top = write_file("chain_top.geo", "Include \"chain_0.geo\";\n");
  EXPECT_NO_THROW(check_geo_script(top, "Include \"chain_0.geo\";\n"));
}

// A second review's findings on the check's memory of files read: a name through a link is
// checked as gmsh reads it (its includes from the link's folder), an Include and a Merge of
// one file are each checked, and a .opt is checked as what its first line makes it.
TEST(MeshReader, EachFileIsCheckedAsGmshWouldReadItFromWhereItIsNamed) {
  const fs::path dir = fs::temp_directory_path() / "dspdem_mesh_reader" / "linked";
  fs::remove_all(dir);
  fs::create_directories(dir / "a");
  fs::create_directories(dir / "b");
  std::ofstream(dir / "b" / "real.geo") << "Include \"y.geo\";\n";
  std::ofstream(dir / "b" / "y.geo") << "Point(1) = {0, 0, 0};\n";
  std::ofstream(dir / "a" / "y.geo") << "Exit;\n";  // what gmsh reads through the link
  fs::create_symlink("../b/real.geo", dir / "a" / "x.geo");
  const std::string text = "Include \"b/real.geo\";\nInclude \"a/x.geo\";\n";
  std::ofstream(dir / "top.geo") << text;
  try {
    check_geo_script((dir / "top.geo").string(), text);
    ADD_FAILURE() << "a/y.geo, read through the link, was not checked";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Exit"), std::string::npos) << e.what();
  }
  // A .opt beginning as a mesh is a mesh to gmsh: checked as one (here a broken one).
  const std::string box = "Point(1) = {0, 0, 0};\n";
  const std::string path = write_file("opt_mesh.geo", box);
  write_file("opt_mesh.geo.opt", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n$EndNodes\n");
  try {
    check_gmsh_option_file(path);
    ADD_FAILURE() << "a .opt holding a broken mesh passed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("opt_mesh.geo.opt"), std::string::npos) << e.what();
  }
  fs::remove(fs::temp_directory_path() / "dspdem_mesh_reader" / "opt_mesh.geo.opt");
}
