// The skeleton `.tree` text format (docs/design.md, "File formats"): one node per line,
// `id parent x y z radius`.
//
//   # a two-element trunk; metres
//   0 -1  0 0 0    0.20
//   2  1  0 0 4.5  0.08
//   1  0  0 0 2.0  0.15
//
//   auto skeleton = fw::trees::read_tree_file("walnut.tree");   // throws base::SourceError on any error
//   fw::trees::write_tree_file(skeleton, "copy.tree");          // exact round trip
//
// - Ids are 0..n-1 for n node lines and become the node indices of the Skeleton; lines may come in any order.
// - parent is -1 for the root (exactly one) or the id of another node; x y z and radius are metres.
// - Fields are separated by spaces or tabs; `#` starts a comment to the end of the line; blank lines and
//   comment-only lines are ignored; CRLF line ends are accepted.
// - Numbers: id and parent are decimal integers; x y z radius are finite decimal numbers (an optional sign,
//   exponent allowed).
//
// Every error throws base::SourceError (an input error, std::invalid_argument: "FILE:LINE: KEY: what was
// expected, got 'TOKEN'"), where KEY is the column: id, parent, x, y, z, radius, or "x y z" for the position
// as a whole (zero-length element). That covers a non-numeric, missing or extra field, a duplicate id, an id
// outside 0..n-1, a parent that is not -1 or an id, a radius <= 0, and the structure: a cycle, two roots or
// none, a node at its parent's position. Structural errors name the line of the offending node. A file
// without node lines is an error too, and an unreadable file gives "FILE: cannot open: REASON".
#pragma once

#include "trees/Skeleton.hpp"

#include <optional>
#include <string>
#include <string_view>

namespace fw::trees {

/// Reads a `.tree` file; see the header comment for the format and the errors (base::SourceError).
Skeleton read_tree_file(const std::string& path);

/// Writes the skeleton as `.tree`, one line per node in id order with full double precision ({:.17g}), so
/// that read_tree_file gives back every value exactly, through base::write_text_atomically (a temporary name,
/// renamed over path); throws std::runtime_error("write_tree_file: cannot write PATH: ...") on failure.
void write_tree_file(const Skeleton& skeleton, const std::string& path);

namespace detail {
// Small text helpers shared by the skeleton readers (TreeFile, QsmImport).

/// The whole file, or base::SourceError("PATH: cannot open: REASON").
std::string read_text_file(const std::string& path);
/// text for an error message: non-printable bytes as \xNN, cut to about 40 characters.
std::string printable(std::string_view text);
/// printable(token) in single quotes: a token as an error message shows it.
std::string quoted(std::string_view token);
/// Throws the file's base::SourceError for a Skeleton::from_nodes error about the parent or the radius of
/// the node read from `line`, whose columns hold the tokens `parent` and `radius`; returns for another
/// field (a position, the node count), which each reader words in its own terms.
void throw_if_parent_or_radius(const SkeletonError& error, const std::string& path, int line,
                               std::string_view parent, std::string_view radius);
}  // namespace detail

}  // namespace fw::trees
