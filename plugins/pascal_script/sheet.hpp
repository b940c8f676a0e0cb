#pragma once
/// \file
/// SimTwo's sheet as a script sees it (simtwo-script-api.md §1.8): text per cell, the number
/// derived from it, buttons (`[caption]`) with their click counters. The numbers of the cells
/// `Global.S2Sheet` defines are also the inputs `sheet/<cell>` (B3 = row 3, column 2), so that
/// `--set`, `--sheet`, `--press`, the viewer and remote clients reach them; `Sheet` keeps the
/// text and the kind.

#include <map>
#include <string>
#include <utility>

namespace s2sim::pascal {

/// "B3" for row 3, column 2 (columns A..Z, AA..).
std::string cell_name(int row, int col);

class Sheet {
 public:
  enum class Kind { text, button, formula };
  struct Cell {
    std::string text;  ///< as set (SimTwo keeps it untrimmed)
    Kind kind = Kind::text;
    double value = 0;  ///< the number derived from the text; a button's clicks live in its input
    int input = -1;    ///< index into the component's sheet inputs, -1 for none
  };

  /// Sets a cell's text and derives its kind and number; setting the same text does nothing
  /// (a button keeps its clicks). Returns the cell.
  Cell& set(int row, int col, const std::string& text);
  /// The cell, or nullptr.
  Cell* find(int row, int col);
  const std::map<std::pair<int, int>, Cell>& cells() const { return cells_; }
  void clear() { cells_.clear(); }

  /// SimTwo's number of a text: the trimmed text as a decimal number, else 0.
  static double parse_number(const std::string& text);

 private:
  std::map<std::pair<int, int>, Cell> cells_;
};

}  // namespace s2sim::pascal
