#pragma once
/// Reading and writing whole files, with errors that name the file; names derived from input
/// made safe to use as file names; outputs staged so a failing command writes nothing.
#include <set>
#include <string>
#include <vector>

namespace coverbench {

/// The bytes of a regular file. Throws InputError naming the path if it is missing, a folder, or
/// cannot be read.
std::string readFile(const std::string& path);

/// A text a user gave us, checked as strict readers require: no NUL byte (a NUL means a binary or
/// truncated file, and parsers would silently stop there) and valid UTF-8. Throws InputError
/// (`source`, "(document)", what and where).
void requireText(const std::string& text, const std::string& source);

/// Whether `text` is valid UTF-8 (no overlong forms, no surrogates, nothing above U+10FFFF).
bool isValidUtf8(const std::string& text);
/// Whether valid UTF-8 `text` is one line of printable characters: no ASCII or C1 control (U+0000
/// to U+001F, U+007F to U+009F), no line or paragraph separator (U+2028, U+2029), and no
/// bidirectional control (U+061C, U+200E, U+200F, U+202A to U+202E, U+2066 to U+2069), which
/// would reorder what a table shows.
bool isPrintableLine(const std::string& text);
/// `bytes` as valid UTF-8 text: every byte that does not begin or continue a valid sequence, and
/// every NUL, replaced by U+FFFD (for untrusted output kept as text: a planner's stderr).
std::string toValidUtf8(const std::string& bytes);

/// A file name made from a name taken from input (a wall's name, a planner label): letters,
/// digits, '.', '-' and '_' are kept, every other byte becomes '_', a leading '.' becomes '_', and
/// the result is at most 80 bytes; never empty. So it never names a folder, a parent ('..'), a
/// hidden file or a path. Every file a command derives from input is named through this.
std::string safeFileName(const std::string& name);

/// safeFileName of each name, made unique (ignoring case, for case-insensitive file systems) by
/// appending "-2", "-3", ... in order. Same names in, same file names out.
std::vector<std::string> uniqueFileNames(const std::vector<std::string>& names);

/// The outputs of one command, written all or nothing. `add` writes each file to a temporary
/// file beside its destination at once (so a full disk or a missing folder fails before anything
/// is published); `commit` renames them all into place. Destroyed without `commit` (an error
/// anywhere), it removes every temporary file and every folder it created.
class OutputFiles {
 public:
  OutputFiles() = default;
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;
  ~OutputFiles();

  /// Creates `path` and its missing parents (removed again unless committed).
  void folder(const std::string& path);
  /// Stages `text` for `path`. Throws InputError naming `path` if it cannot be written, or if
  /// `path` was already staged.
  void add(const std::string& path, const std::string& text);
  /// Renames every staged file into place.
  void commit();

 private:
  struct Staged {
    std::string path, temp;
  };
  std::vector<Staged> staged_;
  std::set<std::string> staged_names_;  ///< their paths, normalised
  std::vector<std::string> created_folders_;  ///< in creation order (parents first)
  bool committed_ = false;
};

/// Writes one file atomically (an OutputFiles of one file).
void writeFileAtomically(const std::string& path, const std::string& text);

}  // namespace coverbench
