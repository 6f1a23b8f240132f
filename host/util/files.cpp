#include "util/files.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "util/error.h"
#include "util/interrupt.h"

namespace strata {

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

Unusable unusableInput(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::is_directory(path, ec)) return Unusable::Directory;
    if (fs::is_regular_file(path, ec) && fs::file_size(path, ec) == 0 && !ec) return Unusable::EmptyFile;
    return Unusable::No;
}

void checkOutputPath(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::is_directory(path, ec)) fail(path, "cannot write the file: it is a directory");
    const fs::path parent = fs::path(path).parent_path();
    const fs::path dir = parent.empty() ? fs::path(".") : parent;
    if (!fs::is_directory(dir, ec))
        fail(path, "cannot write the file: directory '" + dir.string() + "' does not exist");
    if (::access(dir.c_str(), W_OK) != 0)
        fail(path, "cannot write the file: directory '" + dir.string() + "' is not writable");
}

void writeTextAtomically(const std::string& path, const std::string& text) {
    const std::string tmp = path + ".tmp";
    const TempFileGuard guard(tmp);  // removed by a second SIGINT or SIGTERM
    {
        std::ofstream f(tmp);
        f << text;
        if (!f) {
            std::remove(tmp.c_str());
            fail(path, "cannot write the file");
        }
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        std::remove(tmp.c_str());
        fail(path, "cannot write the file");
    }
}

std::string restrictRoot(const std::string& dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path root = fs::canonical(dir, ec);
    if (ec || !fs::is_directory(root, ec))
        fail("strata", "--restrict-paths " + dir + ": not an existing folder");
    return root.string();
}

std::string outsideRoot(const std::string& path, const std::string& root) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::path resolved = fs::weakly_canonical(fs::absolute(path, ec), ec);
    if (ec) resolved = fs::absolute(path, ec).lexically_normal();
    const std::string p = resolved.string();
    const std::string r = root.size() > 1 && root.back() == '/' ? root.substr(0, root.size() - 1) : root;
    const bool inside = p == r || (p.size() > r.size() && p.compare(0, r.size(), r) == 0 &&
                                   (r == "/" || p[r.size()] == '/'));
    return inside ? std::string() : p;
}

}  // namespace strata
