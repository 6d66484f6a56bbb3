// Splits a model's elements among processes with METIS (k-way, on the graph of elements
// joined by a shared face or a joint), so that each process gets about as many elements
// and as few cut faces, hence ghosts to exchange, as METIS can give.
#pragma once
#include <vector>

#include "time/model.hpp"

namespace dspdem::par {

/// The process of every element (global element order), 0 .. parts-1. Deterministic: the
/// same model and count give the same partition on every process (METIS with a fixed seed).
std::vector<int> partition_elements(const Model& m, int parts);

/// Element adjacency as compressed rows (the graph METIS cuts): elements sharing a face
/// (three nodes) or tied by a joint; with contact, also elements of separate pieces that lie
/// close (within about half an element). Exposed for the tests.
void element_graph(const Model& m, std::vector<int>& xadj, std::vector<int>& adjncy);

}  // namespace dspdem::par
