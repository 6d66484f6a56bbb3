// A check of a gmsh .geo script before gmsh runs it. A .geo is a program: besides geometry it
// can run shell commands (SystemCall), write files and folders, set gmsh's own options and end
// the process (Exit, which through gmsh's API ended dspdem with status 0 and no result). A
// case file is often someone else's, run in batch on a shared server or in CI, so the script
// is read as gmsh 4.8's lexer reads it (strings in double or single quotes, no escapes, //
// and /* */ comments) and the commands and options that act outside the model are refused, by
// line, before gmsh reads anything. This guards against the language's commands known to
// act outside the model, and names the line; it is not a sandbox for gmsh's parser or its
// plugins' code. The sandbox is behind it: gmsh reads the file in a child process that the
// kernel stops before it acts outside itself (core/sandbox.hpp, mesh/gmsh_reader.cpp).
#pragma once
#include <string>

namespace dspdem {

/// Throws Error "mesh file '<path>': line <n>: <what>" at the first thing in `text` (the
/// contents of `path`) that gmsh would run outside the model, and "mesh file '<path>': it
/// holds a mesh" if gmsh would read `text` as a mesh or a view by its first line (past the
/// mesh's own check). Refused:
/// - the commands SystemCall, System, NonBlockingSystemCall, OnelabRun, OnelabAction,
///   SendToServer, Exit, Sleep, CreateDir, Save, Print, MergeWithBoundingBox and Plugin, and
///   Printf redirected into a file (> or >>);
/// - S2N and StringToName, which make a command's name from a string; Delete Options (which
///   turns General.AbortOnError off with the other options), Delete All and Delete Model;
/// - the words General and Solver, gmsh's own option categories (General.AbortOnError ends the
///   process on an error; dspdem sets General.NumThreads itself, for the same mesh every run);
/// - Include or Merge of a name the script builds rather than a quoted file name;
/// - a byte gmsh's lexer would read otherwise than this check (NUL and other control
///   characters), a string or comment never closed, and a string over 1023 characters (gmsh
///   reads the rest as code).
/// Words of the first list, General. and Solver. options, and Include, Merge and Printf not
/// read as code are refused in strings and comments too: gmsh's If, For and Macro skip text
/// without reading its strings, so what this reading takes for a string gmsh may run.
/// Files the script includes are checked as scripts, whatever their extension (gmsh parses
/// an Include as a script); a merged .geo or .msh, and a merged file's ".opt", as what its
/// first line makes it (gmsh_reads_as): a script, or a mesh file (format only); merged STEP,
/// BREP, IGES and STL files (extensions spelt as gmsh knows them) are let through, any other
/// kind refused.
void check_geo_script(const std::string& path, const std::string& text);

/// How gmsh 4.8 reads a file by its first line, whatever its extension (.geo and .msh are not
/// told apart by name): a mesh ($MeshFormat, $NOD, $Comments, ...), a post-processing view,
/// or else a script.
enum class GmshText { Mesh, View, Script };
GmshText gmsh_reads_as(const std::string& text);

/// gmsh reads "<file>.opt" beside a file it opens or merges, as a script, and "<file>.opt.opt"
/// beside that, and on: each there is checked as check_geo_script checks a script.
void check_gmsh_option_file(const std::string& file);

}  // namespace dspdem
