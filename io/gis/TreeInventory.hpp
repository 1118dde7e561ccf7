// A forest inventory as a CSV table: one tree a row, where it stands and how big it is, from a field survey
// or a LiDAR segmentation (lidR's crown metrics, a forester's spreadsheet).
//
//   const fw::io::InventoryColumns columns{.height = "Z"};  // the header's names; lidR writes heights as Z
//   const auto inventory = fw::io::read_tree_inventory("trees.csv", columns, {"spruce", "beech"});
//   inventory.trees[0].x, inventory.trees[0].species;       // CRS metres as written; index into the names
//
// The file: a header line of column names, then a row per tree, comma separated. Fields may be quoted as
// R's write.csv and spreadsheets quote them ("Picea abies", "" inside for a quote); CRLF line ends and a
// UTF-8 byte order mark are taken; a quoted field does not span lines; blank lines are skipped; columns the
// mapping does not name are ignored.
// Required columns: x and y (m, in the site's CRS), species (a name the scenario defines), height (m, > 0)
// and dbh (m, > 0, the stem's diameter 1.3 m above its base). Optional: crown_width (m, > 0, or empty) and
// id (any text, unique; the row's number in the file when the column is absent).
//
// Every error throws base::SourceError "FILE:LINE: COLUMN: what was expected, got what", with the column's
// name as the file's header spells it, or "FILE: ..." for a file that cannot be read or holds no tree.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace fw::io {

/// The header's name of each field (case-sensitive, as written).
struct InventoryColumns {
  std::string x = "x", y = "y", species = "species", height = "height", dbh = "dbh";
  std::string crown_width = "crown_width", id = "id";
};

/// One row of the inventory.
struct InventoryTree {
  std::string id;                     ///< the id column's text, or the row's line number
  double x = 0.0, y = 0.0;            ///< m, the site's CRS
  int species = 0;                    ///< index into the species names given to the reader
  double height = 0.0, dbh = 0.0;     ///< m
  std::optional<double> crown_width;  ///< m
  int line = 0;                       ///< its line in the file, for later messages
};

struct TreeInventory {
  std::string file;
  std::vector<InventoryTree> trees;  ///< in the file's order
};

/// Reads `path` by the rules above; `species` are the names a species column may hold. Throws
/// base::SourceError.
TreeInventory read_tree_inventory(const std::string& path, const InventoryColumns& columns,
                                  const std::vector<std::string>& species);

/// The fields of one CSV line (the quoting rules above). Throws base::SourceError at FILE:LINE for an
/// unterminated quote or text after a closing quote.
std::vector<std::string> split_csv_fields(const std::string& line, const std::string& file, int line_number);

}  // namespace fw::io
