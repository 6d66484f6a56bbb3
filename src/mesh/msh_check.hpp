// A check of an ASCII gmsh .msh file (formats 2.x, 4.0 and 4.1) before gmsh reads it.
// gmsh's own reader trusts the file: an element naming a node that $Nodes does not list
// crashes it (a null node in GModel::_associateEntityWithMeshVertices), and the errors it
// does raise name no line ("Error loading '<file>'"). This walks the file once and refuses
// the first line that breaks the format, by number.
#pragma once
#include <string>

namespace dspdem {

/// Throws Error "mesh file '<path>': line <n>: <what is wrong>" at the first line of `text`
/// (the contents of `path`) that breaks the format: sections and their order, counts,
/// numbers, entity, node and element tags, references to nodes and entities. Also refused:
/// sections dspdem does not read (gmsh would interpret them unchecked), format versions
/// other than 2.x, 4.0 and 4.1, and, with `need_volume`, a file without volume (3D) elements
/// (a surface mesh a .geo script merges to build its volume has none). Past their format line,
/// binary files are left to gmsh.
void check_msh_text(const std::string& path, const std::string& text, bool need_volume = true);

}  // namespace dspdem
