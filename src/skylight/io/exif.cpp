#include "skylight/io/exif.h"

#include <fmt/format.h>
#include <libexif/exif-data.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/io/file.h"

namespace skylight::io {
namespace {

struct ExifDataDeleter {
  void operator()(ExifData* d) const { exif_data_unref(d); }
};

// An ASCII entry without its trailing NULs and spaces.
std::optional<std::string> ascii(ExifEntry* e) {
  if (!e || e->format != EXIF_FORMAT_ASCII || !e->data || e->size == 0) return std::nullopt;
  std::string s(reinterpret_cast<const char*>(e->data), e->size);
  while (!s.empty() && (s.back() == '\0' || s.back() == ' ')) s.pop_back();
  if (const auto nul = s.find('\0'); nul != std::string::npos) s.resize(nul);
  // EXIF ASCII is 7-bit: anything else (control characters, other encodings) becomes '?', so
  // no output or message carries it.
  for (char& c : s)
    if (c < 0x20 || c > 0x7e) c = '?';
  if (s.empty()) return std::nullopt;
  return s;
}

// Component i of an (unsigned or signed) RATIONAL entry; nullopt for a zero denominator.
std::optional<double> rational(ExifEntry* e, unsigned i, ExifByteOrder order) {
  if (!e || !e->data || i >= e->components) return std::nullopt;
  const unsigned char* p = e->data + 8 * i;
  if (e->format == EXIF_FORMAT_RATIONAL) {
    const ExifRational r = exif_get_rational(p, order);
    if (r.denominator == 0) return std::nullopt;
    return static_cast<double>(r.numerator) / r.denominator;
  }
  if (e->format == EXIF_FORMAT_SRATIONAL) {
    const ExifSRational r = exif_get_srational(p, order);
    if (r.denominator == 0) return std::nullopt;
    return static_cast<double>(r.numerator) / r.denominator;
  }
  return std::nullopt;
}

// A SHORT or LONG entry's first value.
std::optional<long> integer(ExifEntry* e, ExifByteOrder order) {
  if (!e || !e->data || e->components < 1) return std::nullopt;
  if (e->format == EXIF_FORMAT_SHORT) return exif_get_short(e->data, order);
  if (e->format == EXIF_FORMAT_LONG) return static_cast<long>(exif_get_long(e->data, order));
  return std::nullopt;
}

ExifEntry* entry(ExifData* d, ExifIfd ifd, int tag) {
  return exif_content_get_entry(d->ifd[ifd], static_cast<ExifTag>(tag));
}

// Degrees, minutes, seconds (three rationals) signed by a reference letter (S or W: negative).
std::optional<double> gps_angle(ExifData* d, int tag, int ref_tag, char negative) {
  const ExifByteOrder order = exif_data_get_byte_order(d);
  ExifEntry* e = entry(d, EXIF_IFD_GPS, tag);
  const auto deg = rational(e, 0, order), min = rational(e, 1, order), sec = rational(e, 2, order);
  if (!deg || !min || !sec) return std::nullopt;
  const double v = *deg + *min / 60.0 + *sec / 3600.0;
  const auto ref = ascii(entry(d, EXIF_IFD_GPS, ref_tag));
  return ref && !ref->empty() && (*ref)[0] == negative ? -v : v;
}

bool starts_with(std::span<const char> b, const char* magic, std::size_t n) {
  return b.size() >= n && std::memcmp(b.data(), magic, n) == 0;
}

}  // namespace

ExifInfo read_exif(const std::filesystem::path& path) {
  const std::vector<char> bytes = read_file(path);
  return parse_exif(bytes, shown_path(path));
}

ExifInfo parse_exif(std::span<const char> bytes, std::string_view name_in) {
  const std::string name = excerpt(name_in);
  // libexif reads a JPEG's markers or data that starts with the APP1 payload's "Exif\0\0": a
  // TIFF (or DNG) file is that payload's TIFF structure, so it gets the header in front.
  std::vector<unsigned char> data;
  if (starts_with(bytes, "\xff\xd8", 2)) {
    data.assign(bytes.begin(), bytes.end());
  } else if (starts_with(bytes, "II*\0", 4) || starts_with(bytes, "MM\0*", 4)) {
    // libexif reads the first 65 534 bytes of the TIFF structure (an APP1 segment's limit): a
    // TIFF whose IFD0 lies beyond is refused rather than read as having no EXIF.
    const auto u = [&](std::size_t i) { return static_cast<std::uint32_t>(bytes[i] & 0xff); };
    const std::uint32_t ifd0 = bytes.size() < 8  ? 0
                               : bytes[0] == 'I' ? u(4) | u(5) << 8 | u(6) << 16 | u(7) << 24
                                                 : u(4) << 24 | u(5) << 16 | u(6) << 8 | u(7);
    if (ifd0 >= 0xfffe)
      throw InvalidArgument(fmt::format(
          "'{}': its first IFD lies beyond the first 64 KiB, which libexif does not read; give "
          "the capture's JPEG",
          name));
    const char header[] = {'E', 'x', 'i', 'f', '\0', '\0'};
    data.assign(header, header + 6);
    data.insert(data.end(), bytes.begin(), bytes.end());
  } else {
    throw InvalidArgument(
        fmt::format("'{}': not a JPEG, TIFF or DNG file (no EXIF to read)", name));
  }
  std::unique_ptr<ExifData, ExifDataDeleter> d(exif_data_new());
  if (!d) throw std::bad_alloc();
  // Read what the file says: no entries added or "fixed" to the standard's defaults.
  exif_data_unset_option(d.get(), EXIF_DATA_OPTION_FOLLOW_SPECIFICATION);
  exif_data_load_data(d.get(), data.data(), static_cast<unsigned int>(data.size()));
  bool any = false;
  for (int i = 0; i < EXIF_IFD_COUNT; ++i) any = any || d->ifd[i]->count > 0;
  if (!any) throw InvalidArgument(fmt::format("'{}' carries no EXIF", name));

  ExifData* x = d.get();
  const ExifByteOrder order = exif_data_get_byte_order(x);
  ExifInfo out;
  out.make = ascii(entry(x, EXIF_IFD_0, EXIF_TAG_MAKE)).value_or("");
  out.model = ascii(entry(x, EXIF_IFD_0, EXIF_TAG_MODEL)).value_or("");
  out.date_time = ascii(entry(x, EXIF_IFD_EXIF, EXIF_TAG_DATE_TIME_ORIGINAL));
  out.utc_offset = ascii(entry(x, EXIF_IFD_EXIF, EXIF_TAG_OFFSET_TIME_ORIGINAL));
  out.focal_length_mm = rational(entry(x, EXIF_IFD_EXIF, EXIF_TAG_FOCAL_LENGTH), 0, order);
  const auto resolution =
      rational(entry(x, EXIF_IFD_EXIF, EXIF_TAG_FOCAL_PLANE_X_RESOLUTION), 0, order);
  // FocalPlaneResolutionUnit: 2 inch (the default), 3 centimetre; 4 and 5 (mm, um) are used by
  // some cameras beyond the standard.
  const long unit =
      integer(entry(x, EXIF_IFD_EXIF, EXIF_TAG_FOCAL_PLANE_RESOLUTION_UNIT), order).value_or(2);
  const double mm_per_unit = unit == 3 ? 10.0 : unit == 4 ? 1.0 : unit == 5 ? 1e-3 : 25.4;
  if (out.focal_length_mm && resolution && *out.focal_length_mm > 0.0 && *resolution > 0.0)
    out.focal_length_px = *out.focal_length_mm * *resolution / mm_per_unit;
  if (const auto w = integer(entry(x, EXIF_IFD_EXIF, EXIF_TAG_PIXEL_X_DIMENSION), order);
      w && *w > 0)
    out.pixel_width = static_cast<int>(*w);
  out.latitude_deg = gps_angle(x, EXIF_TAG_GPS_LATITUDE, EXIF_TAG_GPS_LATITUDE_REF, 'S');
  out.longitude_deg = gps_angle(x, EXIF_TAG_GPS_LONGITUDE, EXIF_TAG_GPS_LONGITUDE_REF, 'W');
  if (const auto alt = rational(entry(x, EXIF_IFD_GPS, EXIF_TAG_GPS_ALTITUDE), 0, order)) {
    ExifEntry* ref = entry(x, EXIF_IFD_GPS, EXIF_TAG_GPS_ALTITUDE_REF);
    const bool below = ref && ref->data && ref->size >= 1 && ref->data[0] == 1;
    out.altitude_m = below ? -*alt : *alt;
  }
  return out;
}

std::string ExifInfo::time_iso8601(const std::optional<std::string>& utc_offset_override,
                                   const std::string& name) const {
  if (!date_time)
    throw InvalidArgument(fmt::format("'{}': the EXIF has no DateTimeOriginal", excerpt(name)));
  const std::optional<std::string> offset = utc_offset_override ? utc_offset_override : utc_offset;
  if (!offset)
    throw InvalidArgument(
        fmt::format("'{}': the EXIF time {} has no UTC offset (OffsetTimeOriginal, EXIF 2.31); "
                    "give it with --utc-offset",
                    excerpt(name), excerpt(*date_time)));
  // "YYYY:MM:DD HH:MM:SS" -> "YYYY-MM-DDTHH:MM:SS"; sun::parse_iso8601 checks the rest.
  std::string t = *date_time;
  if (t.size() != 19 || t[4] != ':' || t[7] != ':' || t[10] != ' ')
    throw InvalidArgument(fmt::format("'{}': the EXIF time '{}' is not 'YYYY:MM:DD HH:MM:SS'",
                                      excerpt(name), excerpt(t)));
  t[4] = '-';
  t[7] = '-';
  t[10] = 'T';
  return t + *offset;
}

}  // namespace skylight::io
