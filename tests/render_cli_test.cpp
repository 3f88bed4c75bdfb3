// `softdrop render`: every picture kind from the command line on small scenes, at the asked size
// and print size; animations (GIF and MP4) with one or two droplets; the area trace's marks; the
// paths' colours; and missing or malformed inputs give one line and no picture.
#include <cairo.h>
#include <gif_lib.h>
#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "balloon.hpp"
#include "cli_run.hpp"
#include "csv_table.hpp"
#include "picture_files.hpp"

namespace softdrop {
namespace {

using test::fresh;
using test::Png;
using test::png_dpi;
using test::read_png;

// The command line, one invocation per picture kind, on small scenes.
const std::string kPore = std::string(SOFTDROP_SOURCE_DIR) + "/examples/pore.json";

void expect_png(const std::string& args, const std::string& out, int width) {
  const test::Result r = test::run("render " + args + " -o " + out + " --size " + std::to_string(width));
  ASSERT_EQ(r.code, 0) << args << ": " << r.err;
  const Png png = read_png(out);
  EXPECT_EQ(png.width, width) << args;
  EXPECT_GT(png.non_background, width * 4) << args;
}

TEST(RenderCli, EveryPictureKindRenders) {
  expect_png("medium --medium " + kPore, fresh("cli_medium.png"), 300);
  expect_png("medium --kind non-overlapping --porosity 0.85 --width 200 --height 200", fresh("cli_gen.png"), 240);
  expect_png("snapshots --medium " + kPore + " --x0 100 --times 0.008,0.02,0.03", fresh("cli_snap.png"), 300);
  expect_png("paths --medium " + kPore + " --droplets 6 --seed 2", fresh("cli_paths.png"), 300);

  const std::string db = fresh("cli_search.db");
  ASSERT_EQ(test::run("optimize --db " + db + test::kSmallScene +
                      " --seed 7 --starts 4 --validate-starts 8 "
                      "--stuck-window 0.1 --stuck-distance 1 --generations 8 --quiet")
                .code,
            0);
  const std::string curve = fresh("cli_curve.svg");
  expect_png("search --db " + db + " --run 1 --curve " + curve, fresh("cli_search.png"), 320);
  tinyxml2::XMLDocument doc;
  EXPECT_EQ(doc.LoadFile(curve.c_str()), tinyxml2::XML_SUCCESS);

  const std::string gif = fresh("cli_anim.gif");
  const test::Result r =
      test::run("render animation --medium " + kPore + " --x0 100 --speed 0.01 --fps 10 -o " + gif + " --size 160");
  ASSERT_EQ(r.code, 0) << r.err;
  int error = 0;
  GifFileType* g = DGifOpenFileName(gif.c_str(), &error);
  ASSERT_NE(g, nullptr);
  ASSERT_EQ(DGifSlurp(g), GIF_OK);
  EXPECT_GE(g->ImageCount, 4);  // about 0.039 time units at 0.01 per second, 10 frames a second
  EXPECT_EQ(g->SWidth, 160);
  DGifCloseFile(g, &error);
}

// The second droplet of a pair is drawn in orange, beside the first: the palette's (204, 102, 0),
// entry 4 * 36 + 2 * 6 of its 6 x 6 x 6 cube, which nothing of a one-droplet animation comes to.
TEST(RenderCli, AnAnimationOfTwoDropletsDrawsTheSecondInItsOwnColour) {
  const auto orange_pixels = [](const std::string& gif) {
    int error = 0;
    GifFileType* g = DGifOpenFileName(gif.c_str(), &error);
    EXPECT_NE(g, nullptr);
    if (!g) return -1L;
    EXPECT_EQ(DGifSlurp(g), GIF_OK);
    long most = 0;
    for (int i = 0; i < g->ImageCount; ++i) {
      const SavedImage& frame = g->SavedImages[i];
      const long n = std::count(frame.RasterBits,
                                frame.RasterBits + static_cast<long>(frame.ImageDesc.Width) * frame.ImageDesc.Height,
                                GifByteType{4 * 36 + 2 * 6});
      most = std::max(most, n);
    }
    DGifCloseFile(g, &error);
    return most;
  };
  const std::string args = "render animation --medium " + kPore + " --x0 100 --speed 0.01 --fps 10 --size 240 --quiet";
  const std::string one = fresh("one.gif"), two = fresh("two.gif");
  ASSERT_EQ(test::run(args + " -o " + one).code, 0);
  const test::Result r = test::run(args + " --second-droplet delay --second-after 0.01 -o " + two);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(orange_pixels(one), 0);
  EXPECT_GT(orange_pixels(two), 20);
  // A second droplet that would start inside the first is refused, and no file is written.
  const std::string refused = fresh("refused.gif");
  const test::Result bad = test::run(args + " --second-droplet distance --second-after 3 -o " + refused);
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.err.find("second-after = 3: the second droplet would start overlapping the first"), std::string::npos)
      << bad.err;
  EXPECT_FALSE(std::filesystem::exists(refused));
}

// Progress goes to stderr, as every long command's does; --quiet leaves it out and still draws.
TEST(RenderCli, QuietLeavesOutTheProgressAndStillDraws) {
  for (const std::string kind : {"paths --droplets 4", "animation --x0 100 --speed 0.01 --fps 10"}) {
    SCOPED_TRACE(kind);
    const std::string out = fresh(kind[0] == 'p' ? "quiet.png" : "quiet.gif");
    const std::string args = "render " + kind + " --medium " + kPore + " --size 160 -o " + out;
    const test::Result loud = test::run(args), quiet = test::run(args + " --quiet");
    ASSERT_EQ(loud.code, 0) << loud.err;
    ASSERT_EQ(quiet.code, 0) << quiet.err;
    EXPECT_NE(loud.err.find("render: "), std::string::npos) << loud.err;
    EXPECT_EQ(quiet.err, "");
    EXPECT_GT(std::filesystem::file_size(out), 0u);
  }
}

TEST(RenderCli, AConfigFileReachesTheNestedCommand) {
  const std::string toml = fresh("render.toml"), out = fresh("from_config.png");
  // In a config file a colour goes without its '#' (CLI11's TOML reader takes it for a comment).
  std::ofstream(toml) << "size = 212\nmedium = \"" << kPore << "\"\ngrain-colour = \"ff0000\"\n";
  const test::Result r = test::run("render medium --config " + toml + " -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(read_png(out).width, 212);
  const test::Result before = test::run("--config " + toml + " render medium -o " + out + " --size 180");
  ASSERT_EQ(before.code, 0) << before.err;
  EXPECT_EQ(read_png(out).width, 180) << "the command line wins over the file";
}

TEST(RenderCli, AnimationAsMp4ThroughFfmpeg) {
  const std::string mp4 = fresh("anim.mp4");
  const std::string args =
      "render animation --medium " + kPore + " --x0 100 --speed 0.01 --fps 10 --size 160 -o " + mp4;
  // Without ffmpeg on the PATH: one clear line, no file.
  const test::Result missing = test::run_shell("PATH=/nonexistent " + std::string(SOFTDROP_CLI) + " " + args);
  EXPECT_EQ(missing.code, 1);
  EXPECT_NE(missing.err.find("needs the ffmpeg program"), std::string::npos) << missing.err;
  EXPECT_FALSE(std::filesystem::exists(mp4));
  if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0) GTEST_SKIP() << "ffmpeg is not installed";
  const test::Result r = test::run(args);
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(mp4, std::ios::binary);
  std::string head(12, '\0');
  in.read(head.data(), 12);
  EXPECT_EQ(head.substr(4, 4), "ftyp") << "an ISO media file";
  EXPECT_GT(std::filesystem::file_size(mp4), 1000u);
  // An odd --size gives even frames whose added column and row are background, not dark padding.
  const std::string odd = fresh("odd.mp4"), first = fresh("odd_frame.png");
  ASSERT_EQ(
      test::run("render animation --medium " + kPore + " --x0 100 --speed 0.01 --fps 10 --size 161 -o " + odd).code, 0);
  ASSERT_EQ(std::system(("ffmpeg -loglevel error -y -i " + odd + " -vframes 1 " + first).c_str()), 0);
  cairo_surface_t* s = cairo_image_surface_create_from_png(first.c_str());
  ASSERT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
  const int w = cairo_image_surface_get_width(s), h = cairo_image_surface_get_height(s);
  EXPECT_EQ(w % 2, 0);
  EXPECT_EQ(h % 2, 0);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  auto brightness = [&](int x, int y) {
    const std::uint32_t p = reinterpret_cast<const std::uint32_t*>(data + y * stride)[x];
    return std::min({(p >> 16) & 0xffu, (p >> 8) & 0xffu, p & 0xffu});
  };
  for (int y = 0; y < h; y += 7) EXPECT_GT(brightness(w - 1, y), 200u) << "right column, y = " << y;
  for (int x = 0; x < w; x += 7) EXPECT_GT(brightness(x, h - 1), 200u) << "bottom row, x = " << x;
  cairo_surface_destroy(s);
}

// The area trace through the pore of three grains: its samples, the entry and the exit, and the
// ratio S/S0 between them, lowest and highest.
struct PoreTrace {
  double enter = -1, leave = -1, lowest = 1, highest = 1;
};
PoreTrace trace_through_pore(const std::string& options) {
  const std::string csv = fresh("trace.csv"), png = fresh("trace.png");
  const test::Result r =
      test::run("render trace --medium " + kPore + " --x0 100 --csv " + csv + " -o " + png + " --size 400" + options);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(read_png(png).width, 400);
  EXPECT_NEAR(png_dpi(png), 72, 0.01);  // the default --dpi, written into the file
  const test::CsvTable table = test::read_csv_table(csv);
  PoreTrace p;  // enter, leave: the first sample inside the medium, and below it
  std::vector<double> t, ratio;
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    EXPECT_EQ(table.cell(i, "droplet"), "0");
    t.push_back(table.number(i, "time"));
    ratio.push_back(table.number(i, "area_ratio"));
    const std::string& phase = table.cell(i, "phase");
    if (phase == "inside" && p.enter < 0) p.enter = t.back();
    if (phase == "below" && p.leave < 0) p.leave = t.back();
    EXPECT_TRUE(phase == "above"    ? p.enter < 0
                : phase == "inside" ? p.enter >= 0 && p.leave < 0
                                    : p.leave >= 0)
        << phase;
  }
  EXPECT_GT(t.size(), 50u);
  EXPECT_GT(p.enter, 0);
  EXPECT_GT(p.leave, p.enter);
  EXPECT_LE(p.leave, t.back() + 1e-12);
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] > p.enter && t[i] < p.leave)
      p.lowest = std::min(p.lowest, ratio[i]), p.highest = std::max(p.highest, ratio[i]);
  return p;
}

TEST(RenderCli, AreaTraceMarksEntryAndExitAndTheDropletShrinksAndSwells) {
  // The defaults' springs carry the tension: squeezed through the pore the droplet shrinks, and
  // sprung back it overshoots its rest area.
  const PoreTrace d = trace_through_pore("");
  EXPECT_LT(d.lowest, 0.9) << "squeezing through the pore shrinks the droplet";
  EXPECT_GT(d.highest, 1.02) << "and it swells past its rest area after";
  // The balloon's ring at the stretch limit is the largest, to within what four constraint passes
  // leave of the gas's push in one step (a few 1e-4): it only shrinks.
  const PoreTrace b = trace_through_pore(test::kBalloonOptions);
  EXPECT_LT(b.lowest, 0.95);
  EXPECT_LE(b.highest, 1 + 1e-3);
}

// Overlapping grains are one solid region (one filled path, no outlines); separate grains outlines.
TEST(RenderCli, OverlappingGrainsAreDrawnAsTheirSolidUnion) {
  auto colours = [](const std::string& kind) {
    const std::string svg = fresh("union_" + kind + ".svg");
    EXPECT_EQ(test::run("render medium --kind " + kind +
                        " --porosity 0.8 --width 100 --height 100 --r-min 8 --r-max 16 -o " + svg)
                  .code,
              0);
    std::ifstream in(svg);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    int solid = 0, outlines = 0;
    for (std::size_t at = 0; (at = text.find("rgb(", at)) != std::string::npos; ++at) {
      solid += text.compare(at, 16, "rgb(70%,73%,78%)") == 0;
      outlines += text.compare(at, 14, "rgb(12.156863%") == 0;  // the default grain colour
    }
    return std::pair{solid, outlines};
  };
  EXPECT_EQ(colours("overlapping"), std::pair(1, 0));
  const auto [solid, outlines] = colours("non-overlapping");
  EXPECT_EQ(solid, 0);
  EXPECT_GT(outlines, 3);
}

// --size is in points and --dpi sets a PNG's pixels an inch: the same picture, drawn finer.
TEST(RenderCli, PrintSizesScalePngsAndBadOnesAreRefusedFirst) {
  const std::string png = fresh("print.png");
  ASSERT_EQ(test::run("render medium --medium " + kPore + " --size 200 --dpi 144 --no-caption -o " + png).code, 0);
  EXPECT_EQ(read_png(png).width, 400);
  EXPECT_NEAR(png_dpi(png), 144, 0.01);  // read as drawn, not as 72 dpi
  const std::string db = fresh("print.db"), plot = fresh("print_fit.png");
  ASSERT_EQ(test::run("sweep --db " + db + " --preset quick --porosities 0.8,0.85,0.9,0.95 --quiet").code, 0);
  ASSERT_EQ(test::run("fit --db " + db + " --plot " + plot + " --size 252 --dpi 300").code, 0);
  EXPECT_EQ(read_png(plot).width, 1050);  // 3.5 inches at 300 dpi
  EXPECT_NEAR(png_dpi(plot), 300, 0.01);
  const std::string never = fresh("never_print.png");
  const test::Result bad = test::run("fit --db " + db + " --plot " + never + " --dpi 5000");
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("dpi = 5000: must be in [36, 1200]"), std::string::npos) << bad.err;
  EXPECT_TRUE(bad.out.empty()) << "refused before anything is fitted";
  EXPECT_FALSE(std::filesystem::exists(never));
}

TEST(RenderCli, AScaleBarIsDrawnWhenAsked) {
  const std::string plain = fresh("plain.png"), bar = fresh("bar.png");
  ASSERT_EQ(test::run("render medium --medium " + kPore + " --size 300 --no-caption -o " + plain).code, 0);
  ASSERT_EQ(test::run("render medium --medium " + kPore + " --size 300 --no-caption --scale-bar -o " + bar).code, 0);
  // pore.json is 200 wide: a bar of 20 length units (a tenth of the box's 272 pixels) and its label.
  EXPECT_GT(read_png(bar).non_background, read_png(plain).non_background + 200);
}

// Passed and stuck droplets in their own colours.
// A snapshot's label beside its droplet lies over a halo of the background's colour, so that it
// reads over a grain or the path: in SVG, a stroke painted under the glyphs.
TEST(RenderCli, SnapshotLabelsLieOnAHaloOfTheBackground) {
  const std::string svg = fresh("snapshots_halo.svg");
  ASSERT_EQ(
      test::run("render snapshots --medium " + kPore + " --x0 100 --times 0.01,0.02 --background '#fafaf0' -o " + svg)
          .code,
      0);
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.LoadFile(svg.c_str()), tinyxml2::XML_SUCCESS);
  int labels = 0;
  for (const tinyxml2::XMLElement* e = doc.RootElement()->FirstChildElement("text"); e;
       e = e->NextSiblingElement("text")) {
    if (!e->GetText() || std::string(e->GetText()).rfind("t = ", 0) != 0) continue;
    ++labels;
    EXPECT_STREQ(e->Attribute("stroke"), "rgb(250,250,240)");
    EXPECT_STREQ(e->Attribute("paint-order"), "stroke");
    EXPECT_GT(e->DoubleAttribute("stroke-width"), 1.0);
  }
  EXPECT_EQ(labels, 2);
}

TEST(RenderCli, PathsColourPassedAndStuckDropletsApart) {
  const std::string svg = fresh("paths_colours.svg");
  const test::Result ok = test::run(
      "render paths --porosity 0.75 --width 200 --height 200 --droplets 8 --seed 1 "
      "--r-min 8 --r-max 16 --path-colour '#ff0000' --stuck-colour '#0000ff' -o " +
      svg + test::kBalloonOptions);
  ASSERT_EQ(ok.code, 0) << ok.err;
  std::ifstream in(svg);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("rgb(100%,0%,0%)"), std::string::npos) << "passed paths";
  EXPECT_NE(text.find("rgb(0%,0%,100%)"), std::string::npos) << "stuck paths";
}

// Separate grains are shaded by the share of the droplets that touched them, as in render search;
// overlapping ones, drawn as their union, are not (discs shaded one by one would darken each overlap).
TEST(RenderCli, PathsShadeSeparateGrainsByTheShareOfDropletsThatTouchedThem) {
  const auto draw = [](const std::string& kind, const std::string& svg) {
    const test::Result r = test::run("render paths --kind " + kind +
                                     " --porosity 0.8 --width 200 --height 200 --droplets 8 --seed 1 --r-min 8 "
                                     "--r-max 16 --touched-colour '#00ff00' --quiet -o " +
                                     svg + test::kBalloonOptions);
    EXPECT_EQ(r.code, 0) << r.err;
    tinyxml2::XMLDocument doc;
    EXPECT_EQ(doc.LoadFile(svg.c_str()), tinyxml2::XML_SUCCESS);
    std::ifstream in(svg);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return std::pair{test::count_styled(doc.RootElement(), "fill:rgb(0%,100%,0%)"),
                     text.find("shaded by the share") != std::string::npos};
  };
  const auto [separate_fills, separate_caption] = draw("non-overlapping", fresh("paths_separate.svg"));
  EXPECT_GT(separate_fills, 0);
  EXPECT_TRUE(separate_caption);
  const auto [overlapping_fills, overlapping_caption] = draw("overlapping", fresh("paths_overlapping.svg"));
  EXPECT_EQ(overlapping_fills, 0);
  EXPECT_FALSE(overlapping_caption);
}

// 600 droplets (refused from 417 on while every path was kept whole at its worst case): each finished
// path keeps the points half a pixel apart, and the picture is drawn.
TEST(RenderCli, PathsOfManyDropletsAreDrawn) {
  const std::string png = fresh("paths_1000.png");
  const test::Result ok = test::run(
      "render paths --porosity 0.75 --width 200 --height 200 --droplets 600 --seed 1 "
      "--r-min 8 --r-max 16 --quiet --size 200 -o " +
      png + test::kBalloonOptions);
  ASSERT_EQ(ok.code, 0) << ok.err;
  EXPECT_GT(read_png(png).non_background, 10000);
}

TEST(RenderCli, CurvesDrawSeveralSearchesAndNameWhatTheyCannotDraw) {
  const std::string a = fresh("curves-a-1.db"), b = fresh("curves-a-2.db"), png = fresh("curves.png");
  const std::string search = test::kSmallScene +
                             " --stuck-window 0.1 --starts 4 --validate-starts 4 "
                             "--stuck-distance 1 --generations 3 --quiet";
  for (const auto& [db, seed] : {std::pair{a, 7}, std::pair{b, 8}})
    ASSERT_EQ(test::run("optimize --db " + db + search + " --seed " + std::to_string(seed)).code, 0);
  for (const std::string x : {"evaluations", "seconds"}) {
    const test::Result r = test::run("render curves --db " + a + " --db " + b + " --x " + x + " --size 500 -o " + png);
    ASSERT_EQ(r.code, 0) << r.err;
    const Png p = read_png(png);
    EXPECT_EQ(p.width, 500);
    EXPECT_GT(p.non_background, 2000);
  }
  const test::Result labels = test::run("render curves --db " + a + " --db " + b + " --label one -o " + png);
  EXPECT_EQ(labels.code, 1);
  EXPECT_NE(labels.err.find("label: 1 labels for 2 databases"), std::string::npos) << labels.err;
  ASSERT_EQ(test::run("optimize --db " + a + search + " --seed 9").code, 0);  // a second run in a
  const test::Result two = test::run("render curves --db " + a + " -o " + png);
  EXPECT_EQ(two.code, 1);
  EXPECT_NE(two.err.find("holds 2 runs; choose one with --run ID"), std::string::npos) << two.err;
  EXPECT_EQ(test::run("render curves --db " + a + " --run 2 -o " + png).code, 0);
}

TEST(RenderCli, MissingOrMalformedInputsGiveOneLineAndNoPicture) {
  const std::string bad_grains = fresh("bad_grains.json");
  std::ofstream(bad_grains) << "{\"format\": \"softdrop-medium\", \"version\": 1, \"width\": 10";
  const std::string bad_db = fresh("bad.db");
  std::ofstream(bad_db) << std::string(300, 'x');
  const std::string out = fresh("never.png");
  for (const std::string& args :
       {"medium --medium " + fresh("missing.json"), "medium --medium " + bad_grains,
        "snapshots --medium " + bad_grains + " --times 0.01", "search --db " + fresh("missing.db") + " --run 1",
        "search --db " + bad_db + " --run 1", "medium --medium " + kPore + " --background red",
        "medium --medium " + kPore + " --size 3"}) {
    const test::Result r = test::run("render " + args + " -o " + out);
    SCOPED_TRACE(args);
    EXPECT_NE(r.code, 0);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("softdrop: error: ", 0), 0u) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

}  // namespace
}  // namespace softdrop