#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "cli_run.hpp"
#include "softdrop/medium.hpp"

namespace softdrop {
namespace {

using test::temp_path;

void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

std::string load_error(const std::string& path) {
  try {
    load_medium(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(GrainFile, JsonAndCsvRoundTripExactly) {
  MediumOptions o;
  o.porosity = 0.85;
  o.seed = 3;
  Medium m = generate_medium(o);
  m.periodic = false;
  for (const std::string ext : {".json", ".csv"}) {
    const std::string path = temp_path("roundtrip" + ext);
    save_medium(path, m);
    EXPECT_EQ(load_medium(path), m) << ext;
    std::filesystem::remove(path);
  }
}

// The CSV softdrop writes is one plain table: a header and one row a grain, every row with the box,
// numbers in their shortest exact form. A medium without grains keeps its box in comment lines.
TEST(GrainFile, CsvIsOnePlainTableWithTheBoxOnEveryRow) {
  const std::string path = temp_path("plain.csv");
  save_medium(path, Medium{300, 200, true, {{0.8, 10, 8}, {150.25, 100.5, 16}}, nullptr});
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "x,y,r,width,height,periodic\n0.8,10,8,300,200,true\n150.25,100.5,16,300,200,true\n");
  const Medium empty{40, 30, false, {}, nullptr};
  save_medium(path, empty);
  EXPECT_EQ(load_medium(path), empty);
  write(path, "x,y,r,width,height,periodic\n1,2,3,40,30,false\n5,6,3,40,31,false\n");
  EXPECT_NE(load_error(path).find("line 3: width, height or periodic differ from the rows above"), std::string::npos)
      << load_error(path);
  write(path, "x,y,r,width,height,periodic\n1,2,3,40,30\n");
  EXPECT_NE(load_error(path).find("line 2: expected 6 fields"), std::string::npos) << load_error(path);
  std::filesystem::remove(path);
}

TEST(GrainFile, HandWrittenCsvLoads) {
  const std::string path = temp_path("hand.csv");
  write(path, "# width=200\n# height = 100\n# periodic=false\nx,y,r\n10,20,5\n 30 , 40 , 6\n");
  const Medium m = load_medium(path);
  EXPECT_EQ(m.width, 200);
  EXPECT_EQ(m.height, 100);
  EXPECT_FALSE(m.periodic);
  ASSERT_EQ(m.grains.size(), 2u);
  EXPECT_EQ(m.grains[1], (Grain{30, 40, 6}));
  std::filesystem::remove(path);
}

TEST(GrainFile, BadFilesGiveErrorsNamingTheFile) {
  const std::string missing = temp_path("missing.json");
  EXPECT_NE(load_error(missing).find(missing), std::string::npos);
  struct Bad {
    std::string name, text, expect;
  };
  for (const Bad& b :
       {Bad{"a.json", "{\"format\": \"softdrop-medium\", \"version\": 1", "JSON"},
        Bad{"b.json", "{\"format\": \"other\"}", "format"},
        Bad{"c.json", R"({"format":"softdrop-medium","version":1,"width":10,"height":10,"grains":[{"x":1,"y":2}]})",
            "missing"},
        Bad{"d.csv", "# width=10\n# height=10\nx,y,r\n1,2,abc\n", "line 4"},
        Bad{"e.csv", "# width=10\nx,y,r\n1,2,3\n", "height"},
        Bad{"f.csv", "# width=10\n# height=10\nx,y,r\n1,2,-3\n", "radius"},
        Bad{"g.csv", "# width=10\n# height=10\nx,y\n", "header"},
        Bad{"h.csv", "# width=10\n# height=10\nx,y,r\n1,2,3,4\n", "3 fields"}}) {
    const std::string path = temp_path(b.name);
    write(path, b.text);
    const std::string error = load_error(path);
    EXPECT_NE(error.find(path), std::string::npos) << b.name << ": " << error;
    EXPECT_NE(error.find(b.expect), std::string::npos) << b.name << ": " << error;
    std::filesystem::remove(path);
  }
}

// A database or an image given where grains are expected is said for what it is, whatever its name.
TEST(GrainFile, ADatabaseOrAnImageIsNamedForWhatItIs) {
  struct Binary {
    std::string name, head, expect;
  };
  for (const Binary& b : {Binary{"history.db", std::string("SQLite format 3\0", 16), "is an SQLite database"},
                          Binary{"best.json", std::string("SQLite format 3\0", 16), "softdrop export --db"},
                          Binary{"rock.dat", "\x89PNG\r\n\x1a\n", "name it .png, .tif or .npy"},
                          Binary{"rock.csv", std::string("II*\0", 4), "is an image"},
                          Binary{"rock.json", std::string("MM\0*", 4), "is an image"},
                          Binary{"array.csv", "\x93NUMPY\x01\x00", "numpy array"}}) {
    const std::string path = temp_path(b.name);
    write(path, b.head + std::string(200, 'x'));
    const std::string error = load_error(path);
    EXPECT_EQ(error.rfind("grain file '" + path + "': ", 0), 0u) << b.name << ": " << error;
    EXPECT_NE(error.find(b.expect), std::string::npos) << b.name << ": " << error;
  }
  // Text that merely begins with such letters is read as text.
  const std::string mm = temp_path("mm.csv");
  write(mm, "MM\n");
  EXPECT_NE(load_error(mm).find("expected header"), std::string::npos);
}

TEST(GrainFile, SaveIntoMissingDirectoryFailsAndLeavesNothing) {
  const std::string dir = temp_path("no_such_dir");
  EXPECT_THROW(save_medium(dir + "/m.json", Medium{}), std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(dir));
}

}  // namespace
}  // namespace softdrop
