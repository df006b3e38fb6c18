#include "media/png_writer.hpp"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "io/input_file.hpp"

namespace beltsim {

namespace {

// libpng's error callback must not return: it adds the message to the ones kept and longjmps back
// to the setjmp in the caller (a C++ exception must not cross libpng's C frames), which then throws.
void on_error(png_structp png, png_const_charp msg) {
  auto* where = static_cast<std::string*>(png_get_error_ptr(png));
  if (where) *where += msg;
  png_longjmp(png, 1);
}
void on_warning(png_structp, png_const_charp) {}
// a reader's warnings are kept for its error's message: libpng says why a header is invalid
// ("Image width exceeds user limit in IHDR") as a warning before the error ("Invalid IHDR data")
void keep_warning(png_structp png, png_const_charp msg) {
  auto* where = static_cast<std::string*>(png_get_error_ptr(png));
  if (where) *where += std::string(msg) + "; ";
}

// libpng's output callback: the bytes collected in memory, written whole at the end
void append_bytes(png_structp png, png_bytep data, png_size_t n) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), n);
}
void no_flush(png_structp) {}

// Deflate's densest code, a match of 258 bytes in two bits, packs at most 1032 bytes of data into
// one byte: a PNG of N bytes holds at most 1032·N bytes of rows (a row being its filter byte and
// its pixels), whatever its header claims.
constexpr double kDeflateMaxRatio = 1032;

// why a PNG's header cannot be believed ("" when it can): more pixels than kMaxPngPixels, or rows
// of more bytes than its file can hold
std::string png_size_problem(png_uint_32 width, png_uint_32 height, size_t row_bytes, long file_bytes) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (static_cast<double>(width) * height > kMaxPngPixels)
    return "its header claims " + size + " pixels, more than the " + std::to_string(kMaxPngPixels) +
           " beltsim reads (its own pictures are far smaller)";
  const double rows = static_cast<double>(height) * (1.0 + static_cast<double>(row_bytes));
  if (rows > kDeflateMaxRatio * static_cast<double>(file_bytes))
    return "its header claims " + size + " pixels (" + std::to_string(static_cast<long long>(rows)) +
           " bytes of rows), more than its " + std::to_string(file_bytes) +
           " bytes can hold (deflate packs at most 1032 bytes into one): not a whole PNG";
  return "";
}

// Image::text_boxes as the chunk's text, and back ("x,y,w,h;..."); false when it is not that
std::string boxes_text(const std::vector<PixelRect>& boxes) {
  std::string s;
  for (const PixelRect& r : boxes)
    s += (s.empty() ? "" : ";") + std::to_string(r.x) + "," + std::to_string(r.y) + "," + std::to_string(r.w) + "," +
         std::to_string(r.h);
  return s;
}

bool parse_boxes(const std::string& s, std::vector<PixelRect>& out) {
  const char* p = s.c_str();
  while (*p) {
    long v[4];
    for (int k = 0; k < 4; ++k) {
      if (k > 0 && *p++ != ',') return false;
      char* end = nullptr;
      errno = 0;
      v[k] = std::strtol(p, &end, 10);
      if (end == p || errno || v[k] < -long{kMaxPngSide} || v[k] > 2 * long{kMaxPngSide}) return false;
      p = end;
    }
    if (v[2] <= 0 || v[3] <= 0) return false;
    out.push_back({static_cast<int>(v[0]), static_cast<int>(v[1]), static_cast<int>(v[2]), static_cast<int>(v[3])});
    if (*p && *p++ != ';') return false;  // a ';' between boxes (and one after the last) only
  }
  return true;
}

}  // namespace

void write_png(const std::string& path, const Image& img) {
  const OutputPlace p = output_place(path);
  write_png(p.dir, p.name, img);
}

std::string encode_png(const Image& img, const std::string& what) {
  if (img.width <= 0 || img.height <= 0 || img.rgb.size() != static_cast<size_t>(3) * img.width * img.height)
    throw std::runtime_error(what + ": empty or inconsistent image");
  std::string bytes;
  std::string error;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, on_error, on_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    throw std::runtime_error(what + ": out of memory");
  }
  std::vector<png_bytep> rows(img.height);
  for (int y = 0; y < img.height; ++y) rows[y] = const_cast<png_bytep>(img.pixel(0, y));
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error(what + ": " + error);
  }
  png_set_write_fn(png, &bytes, append_bytes, no_flush);
  // frames are written while the simulation waits: zlib level 3 and the Sub filter only (not
  // libpng's adaptive choice among five per row) halve the time per 1280×720 frame (22 to 11 ms
  // measured); our flat-coloured frames still compress to about 120 kB
  png_set_compression_level(png, 3);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_set_IHDR(png, info, img.width, img.height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  // the text boxes before the pixels (read with the header): a few hundred bytes, stored plain
  std::string boxes = boxes_text(img.text_boxes);
  png_text chunk{};
  if (!boxes.empty()) {
    chunk.compression = PNG_TEXT_COMPRESSION_NONE;
    chunk.key = const_cast<char*>(kTextBoxesKey);
    chunk.text = boxes.data();
    chunk.text_length = boxes.size();
    png_set_text(png, info, &chunk, 1);
  }
  png_write_info(png, info);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return bytes;
}

void write_png(const OutputDir& dir, const std::string& name, const Image& img) {
  const std::string path = dir.file(name);
  if (img.width <= 0 || img.height <= 0 || img.rgb.size() != static_cast<size_t>(3) * img.width * img.height)
    throw std::runtime_error("write_png " + path + ": empty or inconsistent image");
  WholeFile file(dir, name);  // refuses a link before any work
  file.write(encode_png(img, "write_png " + path));
  file.commit();
}

Image read_png(const std::string& path) {
  InputFile file(path);  // a regular file only: a FIFO or a device is not read
  std::string error;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, on_error, keep_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    throw std::runtime_error("read_png " + path + ": out of memory");
  }
  Image img;
  std::vector<png_bytep> rows;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    if (error.find("exceeds user limit") != std::string::npos)
      error += " (beltsim reads at most " + std::to_string(kMaxPngSide) + " pixels a side)";
    throw std::runtime_error("read_png " + path + ": " + error);
  }
  png_init_io(png, file.stream());
  // the header's size is checked before any row is allocated: libpng refuses sides past the limit
  // as it reads the header, and ancillary chunks (text, profiles) past 8 MB
  png_set_user_limits(png, kMaxPngSide, kMaxPngSide);
  png_set_chunk_malloc_max(png, 8u << 20);
  png_read_info(png, info);
  if (const std::string bad = png_size_problem(png_get_image_width(png, info), png_get_image_height(png, info),
                                               png_get_rowbytes(png, info), file.size());
      !bad.empty()) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw std::runtime_error("read_png " + path + ": " + bad);
  }
  const int type = png_get_color_type(png, info);
  if (png_get_bit_depth(png, info) == 16) png_set_strip_16(png);
  if (type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (type == PNG_COLOR_TYPE_GRAY || type == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(png);
  if (png_get_bit_depth(png, info) < 8) png_set_expand(png);
  if (type & PNG_COLOR_MASK_ALPHA) png_set_strip_alpha(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_strip_alpha(png);
  png_read_update_info(png, info);
  img = Image(static_cast<int>(png_get_image_width(png, info)), static_cast<int>(png_get_image_height(png, info)));
  rows.resize(img.height);
  for (int y = 0; y < img.height; ++y) rows[y] = img.pixel(0, y);
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  // the text boxes' chunk, when there is one (read with the header)
  png_textp texts = nullptr;
  int n_texts = 0;
  png_get_text(png, info, &texts, &n_texts);
  std::optional<std::string> boxes;
  for (int k = 0; k < n_texts; ++k)
    if (std::strcmp(texts[k].key, kTextBoxesKey) == 0) boxes.emplace(texts[k].text, texts[k].text_length);
  png_destroy_read_struct(&png, &info, nullptr);
  if (boxes && !parse_boxes(*boxes, img.text_boxes))
    throw std::runtime_error("read_png " + path + ": its " + kTextBoxesKey +
                             " chunk is not a list of x,y,w,h (whole numbers, w and h > 0) separated by ';': '" +
                             boxes->substr(0, 60) + (boxes->size() > 60 ? "...'" : "'"));
  return img;
}

}  // namespace beltsim
