// Import of TreeQSM cylinder tables, the text export of quantitative structure models of laser-scanned trees,
// as a Skeleton.
//
//   radius  length  start_x start_y start_z  axis_x axis_y axis_z  parent  [further columns ignored]
//   0.15    2.0     0 0 0                    0 0 1                 0
//   0.10    1.5     0 0 2                    0 0 1                 1
//   0.05    1.0     0 0 2                    1 0 1                 1
//
//   fw::trees::QsmImportInfo info;
//   auto skeleton = fw::trees::read_qsm_cylinders("walnut_cyl.txt", &info);   // 4 nodes for 3 cylinders
//
// Format:
// - One cylinder per row; fields separated by whitespace, or by commas when the line holds a comma (each
//   field then trimmed of spaces). At least 9 columns: radius (m), length (m), start x y z (m), axis x y z
//   (direction, any length, normalised here) and parent: the 1-based row number of the parent cylinder among
//   the cylinder rows, 0 for none. Further columns (TreeQSM's extension, added, UnmodRadius, branch, ...) are
//   ignored. parent may be written as an integral decimal ("3" or "3.0").
// - An optional header line of non-numeric text before the first row is skipped. Blank lines and `#`
//   comments are ignored.
//
// Mapping: node 0 (the root) is the start point of the one cylinder whose parent is 0, with the radius of the
// first cylinder row. Cylinder k (1-based row number) becomes node k, at its end point start + length * axis
// / |axis|, with the cylinder's radius; its parent node is node j for parent cylinder j (that cylinder's
// end), or the root node 0 for the parentless cylinder. So node indices equal cylinder numbers.
//
// Gaps: a cylinder's start should lie at its parent's end. When it lies farther than 0.1 * length + 1 mm from
// it, the cylinder is still attached to the parent's end node (its start point is dropped): such gaps are
// common in QSM output and not an error. QsmImportInfo counts them.
//
// Every error throws base::SourceError (an input error, std::invalid_argument: "FILE:LINE: COLUMN: what was
// expected, got 'TOKEN'"), COLUMN being one of radius, length, start x|y|z, axis x|y|z, "axis x y z", parent:
// a bad number, too few columns, a parent outside 0..m (m cylinders) or not an integer, no or several
// cylinders with parent 0, a radius or length
// <= 0, a zero axis, and the structure found by Skeleton (a cycle of parents, a cylinder that is its own
// parent, an end point at its parent's end: a zero-length element) on the offending cylinder's line.
#pragma once

#include "trees/Skeleton.hpp"

#include <string>

namespace fw::trees {

/// What read_qsm_cylinders found besides the skeleton.
struct QsmImportInfo {
  int cylinders = 0;  ///< cylinder rows read (= skeleton nodes - 1)
  int gaps = 0;       ///< cylinders whose start is more than 0.1 * length + 1 mm from their parent's end
  double largest_gap = 0.0;  ///< m, largest start-to-parent-end distance over all child cylinders
  int largest_gap_line = 0;  ///< line of that cylinder, 0 when there is none
};

/// Reads a TreeQSM cylinder table; see the header comment for the format, the mapping and the errors.
/// info, when given, receives the counts.
Skeleton read_qsm_cylinders(const std::string& path, QsmImportInfo* info = nullptr);

}  // namespace fw::trees
