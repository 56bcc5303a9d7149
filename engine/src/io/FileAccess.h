// FileAccess.h: how every scene format reads files. A scene file is read only when it is a
// regular file within the size bound (a FIFO or device never blocks the load); a file it names
// (a glTF URI, an OBJ's MTL library, a texture) only when its real path lies inside the scene's
// folder or a folder the user allowed (LoadOptions::allowedFolders), opened without following
// anything swapped in after the check. Messages quote the file's text printably.
#pragma once

#include <lantern/Result.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace lantern::io {

/// Decodes %XX escapes (as tinygltf does before opening a file).
std::string percentDecode(std::string_view text);

/// Checks an external (non-data) URI: it must be a relative path (no scheme, no absolute path)
/// inside the scene's folder: no ".." component, unless `allowParent` (the user allowed other
/// folders; resolveConfined then decides). Returns the decoded relative path, or the reason it
/// is refused as the error message (an InvalidInput error naming `object` and `file`).
Result<std::string> checkRelativeUri(std::string_view uri, const std::string& object,
                                     const std::string& file, bool allowParent = false);

/// Text from a file made safe to quote in a message: control and non-ASCII bytes as \xNN, and
/// cut after `limit` bytes ("..."). A message never carries a file's raw bytes.
std::string printable(std::string_view text, std::size_t limit = 80);

/// A file resolved inside a confining folder: `root` is the folder's real path, `relative` the
/// file's real path below it (no symbolic link, no "..").
struct ConfinedPath {
    std::filesystem::path root, relative;
    std::filesystem::path real() const;
};

/// An external file a URI names, resolved and confined: `relative` (a checked relative path)
/// is resolved to its real path (every symlink followed) and refused unless that lies inside
/// the scene's real folder or one of the `allowed` folders' and is a regular file (not a
/// folder, FIFO, socket or device) of at most `maxBytes`. The error message names the URI and
/// the reason, never the file's bytes. Read it with readConfinedFile.
Result<ConfinedPath> resolveConfined(const std::filesystem::path& folder,
                                              const std::string& relative,
                                              std::uint64_t maxBytes,
                                              const std::vector<std::filesystem::path>& allowed = {});

/// Reads a regular file of at most `maxBytes`: opened with O_NONBLOCK (a FIFO or device never
/// blocks) and, when `noFollow`, O_NOFOLLOW (the last component may not be a symlink); the
/// opened file is checked with fstat before a byte is read. The error message names the reason.
Result<std::vector<unsigned char>> readRegularFile(const std::filesystem::path& path,
                                                   std::uint64_t maxBytes, bool noFollow);

/// Reads a file resolveConfined found, without the window between its check and the open: the
/// path is opened one component at a time from the confining folder, each with O_NOFOLLOW
/// (openat), so a folder swapped for a symbolic link after the check is refused, not
/// followed. Then as readRegularFile.
Result<std::vector<unsigned char>> readConfinedFile(const ConfinedPath& file,
                                                    std::uint64_t maxBytes);

/// The first `count` bytes of a regular file (fewer when it is shorter), opened as
/// readRegularFile opens it: a folder, FIFO or device is refused, never waited on.
Result<std::string> readFileStart(const std::filesystem::path& path, std::size_t count);

} // namespace lantern::io
