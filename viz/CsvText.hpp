// The comma-separated files a run writes (probes.csv, damage.csv) as text: their lines and each line's
// values. Quotes as RFC 4180 has them: damage.csv quotes an inventory id that holds a comma or a quote;
// every other name with a comma is refused where it is given.
//
//   const std::vector<std::string> lines = fw::viz::csv_lines(text, /*keep_unfinished_last=*/true);
//   const std::vector<std::string> header = fw::viz::split_csv(lines.at(0), "damage.csv", 1);
#pragma once

#include <string>
#include <vector>

namespace fw::viz {

/// The lines of `text` without their '\n' line ends: line n + 1 of the file is element n. A last line
/// without its line end is kept when `keep_unfinished_last` (a file written whole, through a rename) and
/// left out otherwise (a file appended row by row, whose last row a killed run may have cut short).
std::vector<std::string> csv_lines(const std::string& text, bool keep_unfinished_last);

/// The values of line `line_number` of `file` between its commas, quotes read as io::split_csv_fields reads
/// them (io/gis/TreeInventory.hpp): "a,,b" gives a, "", b; "a," gives a, ""; "" gives none;
/// "\"x,\"\"y\"\"\",b" gives x,"y" and b. Throws base::SourceError at FILE:LINE for a quote left open.
std::vector<std::string> split_csv(const std::string& line, const std::string& file, int line_number);

}  // namespace fw::viz
