#pragma once
// Internal to the glTF loader: what the validator found (core/gltf/validate/validate.h) and what
// the loader made of it. The loader calls use(pointer) for every element it reads, before reading
// it: the first issue at or below that pointer is thrown as the error of the file, unless it
// concerns only an extension irad ignores (then it is a warning naming the extension) or its code
// is one the loader repairs (then it is a warning naming the repair). At the end, warn_unused()
// reports the issues of the elements irad never used as one warning line that counts them and
// shows the first.
#include "core/gltf/validate/validate.h"
#include "core/util/log.h"

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace irad::gltf {

class IssueBook {
public:
  // supported(name): whether irad reads the content of extension `name`. An issue concerns only
  // an ignored extension when its pointer lies in the object of an unsupported one
  // (".../extensions/NAME..."), or when it is raised by unsupported extensions alone
  // (Issue::extensions). A required unsupported extension is the file's error before any use
  // (core/gltf/loader.cpp check_extensions): the ignored extensions are those irad may skip.
  IssueBook(std::string file, std::vector<Issue> issues,
            std::function<bool(const std::string&)> supported);

  // Adds an issue found while resolving the document (buffers, images), kept in pointer order.
  void add(Issue issue);
  // Throws Error(file, path, message) for the first issue at or below `pointer` that is neither
  // repaired nor within an ignored extension; warns once for each of those there, with one line
  // "FILE: PATH: message; REPAIR" or "FILE: PATH: message; irad ignores extension 'NAME'".
  // Issues are used at most once. exact: only issues at `pointer` itself, not below it.
  void use(const std::string& pointer, Log& log, bool exact = false);
  // One warning for every issue no use() reached: "N problems in parts irad does not use; the
  // first: PATH: message (CODE)".
  void warn_unused(Log& log) const;
  std::size_t size() const { return issues_.size(); }

private:
  struct Entry {
    Issue issue;
    bool used = false;
  };
  // The unsupported extension the issue concerns alone (the outermost one on its pointer, else
  // the first of Issue::extensions when none of them is supported); nullopt otherwise.
  std::optional<std::string> ignored_extension(const Issue& issue) const;

  std::string file_;
  std::function<bool(const std::string&)> supported_;
  std::multimap<std::string, Entry> issues_; // by pointer
};

// The repair the loader makes for a problem of this code, or nullptr when it has none (the
// problem is then an error wherever irad uses the element).
const char* repair_of(const std::string& code);

} // namespace irad::gltf
