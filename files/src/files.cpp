#include "coverbench/files.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include "coverbench/input_error.hpp"

namespace coverbench {

namespace fs = std::filesystem;

std::string readFile(const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) throw InputError(path, "(file)", "cannot be read: no such file");
  if (fs::is_directory(st)) throw InputError(path, "(file)", "cannot be read: it is a folder, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "(file)", "cannot be read");
  std::stringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw InputError(path, "(file)", "cannot be read: read error");
  return ss.str();
}

bool isPrintableLine(const std::string& text) {
  const auto byte = [&](std::size_t i) { return i < text.size() ? static_cast<unsigned char>(text[i]) : 0; };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned char a = byte(i), b = byte(i + 1), c = byte(i + 2);
    if (a < 0x20 || a == 0x7f) return false;
    if (a == 0xc2 && b >= 0x80 && b <= 0x9f) return false;                          // U+0080 .. U+009F
    if (a == 0xd8 && b == 0x9c) return false;                                       // U+061C
    if (a == 0xe2 && b == 0x80 && (c == 0x8e || c == 0x8f || (c >= 0xa8 && c <= 0xae))) return false;  // U+200E/F, U+2028 .. U+202E
    if (a == 0xe2 && b == 0x81 && c >= 0xa6 && c <= 0xa9) return false;            // U+2066 .. U+2069
  }
  return true;
}

bool isValidUtf8(const std::string& text) {
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n;) {
    const unsigned char c = s[i];
    if (c < 0x80) {
      ++i;
      continue;
    }
    std::size_t len = 0;
    unsigned long cp = 0;
    if ((c & 0xE0) == 0xC0) len = 2, cp = c & 0x1F;
    else if ((c & 0xF0) == 0xE0) len = 3, cp = c & 0x0F;
    else if ((c & 0xF8) == 0xF0) len = 4, cp = c & 0x07;
    else return false;
    if (i + len > n) return false;
    for (std::size_t k = 1; k < len; ++k) {
      if ((s[i + k] & 0xC0) != 0x80) return false;
      cp = (cp << 6) | (s[i + k] & 0x3F);
    }
    const unsigned long min_cp = len == 2 ? 0x80 : len == 3 ? 0x800 : 0x10000;
    if (cp < min_cp || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
    i += len;
  }
  return true;
}

std::string toValidUtf8(const std::string& bytes) {
  static const std::string kReplacement = "\xEF\xBF\xBD";
  const auto* s = reinterpret_cast<const unsigned char*>(bytes.data());
  const std::size_t n = bytes.size();
  std::string out;
  out.reserve(n);
  for (std::size_t i = 0; i < n;) {
    const unsigned char c = s[i];
    if (c == 0) {
      out += kReplacement;
      ++i;
      continue;
    }
    std::size_t len = c < 0x80 ? 1 : (c & 0xE0) == 0xC0 ? 2 : (c & 0xF0) == 0xE0 ? 3 : (c & 0xF8) == 0xF0 ? 4 : 0;
    if (len > 1 && i + len <= n && isValidUtf8(bytes.substr(i, len))) {
      out.append(bytes, i, len);
      i += len;
    } else if (len == 1) {
      out += static_cast<char>(c);
      ++i;
    } else {  // one byte that starts no valid sequence here
      out += kReplacement;
      ++i;
    }
  }
  return out;
}

void requireText(const std::string& text, const std::string& source) {
  const std::size_t nul = text.find('\0');
  if (nul != std::string::npos)
    throw InputError(source, "(document)", "contains a NUL byte at offset " + std::to_string(nul) + " (not a text file)");
  if (!isValidUtf8(text)) throw InputError(source, "(document)", "is not valid UTF-8 text");
}

std::string safeFileName(const std::string& name) {
  std::string out;
  for (char c : name) {
    const auto u = static_cast<unsigned char>(c);
    out += (u < 0x80 && (std::isalnum(u) || c == '.' || c == '-' || c == '_')) ? c : '_';
    if (out.size() == 80) break;
  }
  if (out.empty()) out = "_";
  if (out[0] == '.') out[0] = '_';
  return out;
}

std::vector<std::string> uniqueFileNames(const std::vector<std::string>& names) {
  std::vector<std::string> out;
  std::set<std::string> taken;  // lower case
  auto lower = [](std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  for (const std::string& name : names) {
    const std::string base = safeFileName(name);
    std::string candidate = base;
    for (int k = 2; !taken.insert(lower(candidate)).second; ++k) candidate = base + "-" + std::to_string(k);
    out.push_back(candidate);
  }
  return out;
}

OutputFiles::~OutputFiles() {
  if (committed_) return;
  for (const Staged& s : staged_) std::remove(s.temp.c_str());
  std::error_code ec;
  for (auto it = created_folders_.rbegin(); it != created_folders_.rend(); ++it) fs::remove(*it, ec);  // only if empty
}

void OutputFiles::folder(const std::string& path) {
  std::vector<fs::path> missing;
  for (fs::path p = fs::path(path).lexically_normal(); !p.empty() && !fs::exists(p); p = p.parent_path()) {
    missing.push_back(p);
    if (p == p.parent_path()) break;
  }
  std::error_code ec;
  fs::create_directories(path, ec);
  if (ec) throw InputError(path, "(folder)", "cannot be created: " + ec.message());
  if (!fs::is_directory(path)) throw InputError(path, "(folder)", "exists and is not a folder");
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) created_folders_.push_back(it->string());
}

void OutputFiles::add(const std::string& path, const std::string& text) {
  // A set, not a scan of what is staged: a dataset of 10 000 walls took 46 s comparing each new
  // file with every earlier one.
  if (!staged_names_.insert(fs::path(path).lexically_normal().string()).second)
    throw InputError(path, "(file)", "is written twice by this command");
  const fs::path dest(path);
  if (fs::is_directory(dest)) throw InputError(path, "(file)", "cannot be written: it is a folder");
  const std::string temp =
      (dest.parent_path() / ("." + dest.filename().string() + ".part-" + std::to_string(::getpid()))).string();
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path, "(file)", "cannot be written (does its folder exist?)");
    staged_.push_back({path, temp});
    out << text;
    out.flush();
    if (!out) throw InputError(path, "(file)", std::string("write failed: ") + std::strerror(errno));
  }
}

void OutputFiles::commit() {
  for (const Staged& s : staged_)
    if (std::rename(s.temp.c_str(), s.path.c_str()) != 0)
      throw InputError(s.path, "(file)", std::string("cannot be written: ") + std::strerror(errno));
  committed_ = true;
}

void writeFileAtomically(const std::string& path, const std::string& text) {
  OutputFiles out;
  out.add(path, text);
  out.commit();
}

}  // namespace coverbench
