#pragma once
/// One escaping function per output format. Every writer puts text that came from input (wall
/// names, experiment names, planner labels, reasons) through the function of its format, so no
/// input can become markup, break a table row, or end a comment.
#include <string>

namespace coverbench {

/// HTML and SVG (XML) text and attribute values: & < > " ' as entities; control characters
/// (newlines included) as spaces.
std::string escapeHtml(const std::string& text);

/// Markdown inline text (a table cell, the rest of a heading; never the start of a line): the
/// characters CommonMark gives a meaning inline (\ ` * _ [ ] < > | & ~) are backslash-escaped,
/// except '_' inside a word (which CommonMark never reads as emphasis); control characters
/// (newlines included) become spaces, so a cell stays on its row.
std::string escapeMarkdown(const std::string& text);

/// LaTeX text (also inside a `%` comment line): the ten special characters and < > | as
/// commands; control characters (newlines included) as spaces, so nothing ends a comment.
std::string escapeLatex(const std::string& text);

/// A CSV field (RFC 4180): quoted when it holds a comma, quote, CR or LF; quotes doubled.
std::string escapeCsv(const std::string& text);

}  // namespace coverbench
