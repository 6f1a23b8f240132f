#include "util/files.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "util/error.h"

namespace strata {

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

void writeTextAtomically(const std::string& path, const std::string& text) {
    const std::string tmp = path + ".tmp";
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

}  // namespace strata
