// Memory order of a mesh. gmsh numbers the elements and nodes of an unstructured volume
// mesh with little regard to where they are, so an element's nodes, and the two sides of a
// joint, lie far apart in memory; after joint insertion the joint kernel spent a quarter of
// its time waiting for node positions (issue 19). Ordering the elements along a Hilbert
// curve through their centroids (CGAL's spatial sorting) and numbering the nodes in order
// of first use puts neighbours next to each other. Tags (gmsh's numbers, used in messages)
// travel with their elements and nodes.
#pragma once
#include "mesh/mesh.hpp"

namespace dspdem {

/// Reorders each block's elements along a Hilbert curve through their centroids, then
/// renumbers the nodes in order of first use by the elements (blocks in order; nodes used
/// by no element keep their relative order at the end). Groups are rewritten to match.
/// Deterministic: the same mesh always gives the same order.
void order_for_locality(Mesh& mesh);

}  // namespace dspdem
