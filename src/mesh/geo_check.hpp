// A check of a gmsh .geo script before gmsh runs it. A .geo is a program: besides geometry it
// can run shell commands (SystemCall), write, create and remove files, and end the process
// (Exit, which through gmsh's API ended dspdem with status 0 and no result). A case file
// is often someone else's, run in batch on a shared server or in CI, so the commands that act
// outside the model are refused, by line, before gmsh reads anything. This is a guard against
// the script language's own commands, not a sandbox: gmsh's parser is not.
#pragma once
#include <string>

namespace dspdem {

/// Throws Error "mesh file '<path>': line <n>: <what>" at the first use in `text` (the
/// contents of `path`) of a command that runs a program or acts on files or the process:
/// SystemCall, NonBlockingSystemCall, OnelabRun, Exit, CreateDir, DeleteFile, RenameFile,
/// Save, Print, Printf redirected into a file (> or >>), and Include or Merge of a name that is
/// not a quoted file name. Files a script includes or merges are checked as they would be
/// read: a .geo as a script, a .msh with check_msh_text; CAD and STL files are let through,
/// any other kind refused.
void check_geo_script(const std::string& path, const std::string& text);

}  // namespace dspdem
