#pragma once
// A minimal RGB raster with lines and a 5x7 bitmap font of every printable ASCII character
// (font5x7.cpp), written as PNG with zlib: enough to
// draw a Campbell diagram without an external plotting program.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace ffr::info {

struct Rgb {
  std::uint8_t r, g, b;
};

class Canvas {
 public:
  Canvas(int width, int height, Rgb background = {255, 255, 255});
  int width() const { return w_; }
  int height() const { return h_; }
  void set(int x, int y, Rgb c);
  Rgb get(int x, int y) const;
  /// A line of the given thickness (pixels); dashed when dash > 0 (dash length in pixels).
  void line(double x0, double y0, double x1, double y1, Rgb c, int thickness = 1, int dash = 0);
  void fill_rect(int x0, int y0, int x1, int y1, Rgb c);
  /// Text with its top-left corner at (x, y); each font pixel is scale x scale.
  void text(int x, int y, const std::string& s, Rgb c, int scale = 2);
  static int text_width(const std::string& s, int scale = 2) { return static_cast<int>(s.size()) * 6 * scale; }
  /// The PNG file's bytes (8-bit RGB, no interlace).
  std::vector<std::uint8_t> png() const;

 private:
  int w_, h_;
  std::vector<std::uint8_t> rgb_;
};

/// Writes atomically (temporary name, rename). Throws std::runtime_error on failure.
void write_png(const Canvas& canvas, const std::filesystem::path& path);

}  // namespace ffr::info
