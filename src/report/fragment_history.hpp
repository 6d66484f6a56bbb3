// Fragments over time, for any scene: every run writes fragments.csv (per frame the
// fragment count and the largest pieces, src/run/run_case.cpp), so a report can follow the
// break-up frame by frame without reading the frames back. fragment_stats.hpp reads one
// frame whole (every piece); this reads every frame's largest pieces.
#pragma once
#include <string>
#include <vector>

namespace dspdem::report {

struct FragmentFrame {
  struct Piece {
    double mass = 0;  ///< [kg]
    int elements = 0;
    double x = 0, y = 0, z = 0;  ///< centre of mass [m]
  };
  int frame = 0;
  double time = 0;             ///< [s]
  long count = 0;              ///< every fragment of the frame
  std::vector<Piece> largest;  ///< the largest pieces listed (up to 20), largest first

  /// Pieces of at least `mass` among those listed: exact when `mass` is above the smallest
  /// listed piece's mass or every piece is listed, a lower bound otherwise.
  int count_at_least(double mass) const;
  /// Mass of the k-th largest piece (0 the largest), 0 if fewer are listed.
  double mass(std::size_t k) const { return k < largest.size() ? largest[k].mass : 0.0; }
};

/// The frames of a run's fragments.csv in order. Throws Error naming the file and what is
/// missing (the file, a column) or wrong (frames out of order, a frame's rows out of rank
/// order: the data row, counted from 1 after the header).
std::vector<FragmentFrame> fragment_history(const std::string& fragments_csv);

}  // namespace dspdem::report
