#include "wal_file.hpp"

#include <array>
#include <fstream>
#include <vector>

namespace softdrop::detail {
namespace {

// The WAL format (sqlite.org/fileformat2.html#walformat): a 32-byte header, then frames of a
// 24-byte header and one page. Header and frame-header fields are big-endian; the checksums run
// over 32-bit words in the byte order the magic number names, each frame's continuing from the
// frame before (the first from the header's).
constexpr std::uint32_t kMagicLittle = 0x377f0682, kMagicBig = 0x377f0683, kFormat = 3007000;
constexpr std::int64_t kHeaderBytes = 32, kFrameHeaderBytes = 24;

std::uint32_t big_endian(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | std::uint32_t{p[3]};
}
std::uint32_t little_endian(const unsigned char* p) {
  return (std::uint32_t{p[3]} << 24) | (std::uint32_t{p[2]} << 16) | (std::uint32_t{p[1]} << 8) | std::uint32_t{p[0]};
}

struct Checksum {
  std::uint32_t s1 = 0, s2 = 0;
  bool big = false;
  // SQLite's walChecksumBytes: pairs of words, n a multiple of 8.
  void add(const unsigned char* p, std::size_t n) {
    for (std::size_t i = 0; i + 8 <= n; i += 8) {
      const std::uint32_t x0 = big ? big_endian(p + i) : little_endian(p + i);
      const std::uint32_t x1 = big ? big_endian(p + i + 4) : little_endian(p + i + 4);
      s1 += x0 + s2;
      s2 += x1 + s1;
    }
  }
};

}  // namespace

WalReport read_wal(const std::string& wal_path) {
  WalReport r;
  std::ifstream in(wal_path, std::ios::binary);
  if (!in) return r;
  std::array<unsigned char, kHeaderBytes> h{};
  if (!in.read(reinterpret_cast<char*>(h.data()), kHeaderBytes)) return r;  // no frames can follow
  in.seekg(0, std::ios::end);
  const std::int64_t size = in.tellg();
  if (size <= kHeaderBytes) return r;
  r.present = true;
  r.bytes = size;

  const std::uint32_t magic = big_endian(&h[0]), page = big_endian(&h[8]);
  const std::uint32_t salt1 = big_endian(&h[16]), salt2 = big_endian(&h[20]);
  Checksum sum;
  sum.big = magic == kMagicBig;
  sum.add(h.data(), 24);
  const bool page_ok = page >= 512 && page <= 65536 && (page & (page - 1)) == 0;
  r.header_valid = (magic == kMagicLittle || magic == kMagicBig) && big_endian(&h[4]) == kFormat && page_ok &&
                   sum.s1 == big_endian(&h[24]) && sum.s2 == big_endian(&h[28]);
  if (!page_ok) return r;  // frames cannot even be told apart
  const std::int64_t frame_bytes = kFrameHeaderBytes + page;
  r.frames = (size - kHeaderBytes) / frame_bytes;

  std::vector<unsigned char> frame(static_cast<std::size_t>(frame_bytes));
  in.seekg(kHeaderBytes);
  bool chain_intact = r.header_valid;
  for (std::int64_t i = 1; i <= r.frames; ++i) {
    if (!in.read(reinterpret_cast<char*>(frame.data()), frame_bytes)) break;
    const unsigned char* f = frame.data();
    const bool this_log = big_endian(f + 8) == salt1 && big_endian(f + 12) == salt2;
    const bool commit = big_endian(f + 4) != 0;
    if (chain_intact) {
      sum.add(f, 8);
      sum.add(f + kFrameHeaderBytes, page);
      if (this_log && big_endian(f) != 0 && sum.s1 == big_endian(f + 16) && sum.s2 == big_endian(f + 20)) {
        ++r.valid_frames;
        continue;
      }
      chain_intact = false;  // recovery stops here
      r.first_bad_frame = i;
      if (!this_log) break;  // the end of this log: what follows is an earlier one's leftovers
      continue;              // a bad commit frame of the last transaction is a write cut short
    }
    if (this_log && commit) ++r.lost_commits;
  }
  if (!r.header_valid && r.first_bad_frame < 0 && r.frames > 0) r.first_bad_frame = 1;
  return r;
}

std::string wal_damage(const WalReport& r) {
  if (!r.present) return "";
  if (!r.header_valid)
    return "its header is damaged, so SQLite would ignore all " + std::to_string(r.bytes) + " bytes of it";
  if (r.lost_commits == 0) return "";
  return "frame " + std::to_string(r.first_bad_frame) + " of " + std::to_string(r.frames) +
         " fails its checksum, so SQLite would drop the " + std::to_string(r.lost_commits) +
         " committed transactions after it";
}

}  // namespace softdrop::detail
