#include "media/jpeg_writer.hpp"

#include <turbojpeg.h>

#include <stdexcept>

namespace beltsim {

std::string encode_jpeg(const Image& img, int quality, const std::string& what) {
  if (img.width <= 0 || img.height <= 0 || img.rgb.size() != static_cast<size_t>(3) * img.width * img.height)
    throw std::runtime_error(what + ": empty or inconsistent image");
  tjhandle h = tjInitCompress();
  if (!h) throw std::runtime_error(what + ": " + tjGetErrorStr2(nullptr));
  unsigned char* out = nullptr;
  unsigned long size = 0;
  const int bad = tjCompress2(h, img.rgb.data(), img.width, 3 * img.width, img.height, TJPF_RGB, &out, &size,
                              TJSAMP_444, quality, TJFLAG_FASTDCT);
  std::string bytes;
  const std::string error = bad ? tjGetErrorStr2(h) : "";
  if (!bad) bytes.assign(reinterpret_cast<const char*>(out), size);
  tjFree(out);
  tjDestroy(h);
  if (bad) throw std::runtime_error(what + ": " + error);
  return bytes;
}

}  // namespace beltsim
