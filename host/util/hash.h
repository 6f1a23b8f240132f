// A 64-bit hash of a stream of bytes, for state files' checksums and a
// scene's content (render/state.h): fast, and any change of the bytes changes
// it with overwhelming likelihood. Not for adversaries.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace strata {

class Hash64 {
public:
    void add(const void* data, std::size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        length_ += bytes;
        while (bytes > 0 && fill_ > 0) {  // complete a word begun by an earlier call
            word_ |= std::uint64_t(*p++) << (8 * fill_);
            fill_ = (fill_ + 1) % 8;
            --bytes;
            if (fill_ == 0) mix(word_), word_ = 0;
        }
        for (; bytes >= 8; bytes -= 8, p += 8) {
            std::uint64_t w;
            std::memcpy(&w, p, 8);
            mix(w);
        }
        for (; bytes > 0; --bytes) word_ |= std::uint64_t(*p++) << (8 * fill_++);
    }
    template <class T>
    void addVector(const std::vector<T>& v) {
        const std::uint64_t n = v.size();
        add(&n, sizeof n);
        add(v.data(), v.size() * sizeof(T));
    }
    void addString(const std::string& s) {
        const std::uint64_t n = s.size();
        add(&n, sizeof n);
        add(s.data(), s.size());
    }
    std::uint64_t digest() const {
        std::uint64_t h = h_;
        if (fill_ > 0) h = step(h, word_);
        return finish(h ^ length_);
    }
    // The digest as 16 hex digits.
    std::string hex() const {
        static const char* digits = "0123456789abcdef";
        std::string s(16, '0');
        std::uint64_t d = digest();
        for (int i = 15; i >= 0; --i, d >>= 4) s[i] = digits[d & 15];
        return s;
    }

private:
    static std::uint64_t step(std::uint64_t h, std::uint64_t w) {
        h ^= w * 0x9e3779b97f4a7c15ull;
        h = (h << 29) | (h >> 35);
        return h * 0xbf58476d1ce4e5b9ull + 0x94d049bb133111ebull;
    }
    static std::uint64_t finish(std::uint64_t x) {  // splitmix64's finalizer
        x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
        x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
        return x ^ (x >> 31);
    }
    void mix(std::uint64_t w) { h_ = step(h_, w); }
    std::uint64_t h_ = 0x243f6a8885a308d3ull;
    std::uint64_t word_ = 0;
    std::uint64_t length_ = 0;
    unsigned fill_ = 0;
};

}  // namespace strata
