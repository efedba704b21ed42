// Atomic writes (SPEC §15) and their temporaries (names that fit, stale ones cleaned).
#include "util/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "scratch_directory.h"

namespace candela {
namespace {

namespace fs = std::filesystem;
using testing::ScratchDirectory;

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A process id that no process has: a child that has exited and been reaped.
pid_t ended_process_id() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

TEST(AtomicFile, ATargetNameOfTheFullLengthIsWritten) {
  // The temporary was once ".tmp-PID-" + the name: 250 bytes became 264, past the
  // file system's 255, and the write failed after the work.
  ScratchDirectory scratch("candela-atomic");
  const fs::path target = scratch.path() / (std::string(250, 'a') + ".png");
  EXPECT_EQ(atomic_write_problem(target.string()), "");
  write_text_atomically(target.string(), "picture");
  EXPECT_EQ(read_all(target), "picture");
  const std::string temporary = fs::path(temporary_path_for(target.string())).filename().string();
  EXPECT_LE(temporary.size(), 5u + 10u + 1u + 16u + 4u) << temporary;
  EXPECT_EQ(fs::path(temporary).extension(), ".png");  // writers that choose the format by it
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(scratch.path())) ++files;
  EXPECT_EQ(files, 1u);  // no temporary left
}

TEST(AtomicFile, ANameLongerThanTheFolderAllowsIsAProblemBeforeTheWork) {
  ScratchDirectory scratch("candela-atomic");
  const std::string target = (scratch.path() / (std::string(252, 'b') + ".png")).string();
  const std::string problem = atomic_write_problem(target);
  EXPECT_NE(problem.find("longer than the folder allows (256 bytes, at most 255)"), std::string::npos)
      << problem;
  EXPECT_NE(atomic_write_problem((scratch.path() / "missing" / "x.png").string()), "");
  EXPECT_EQ(atomic_write_problem((scratch.path() / "fine.png").string()), "");
  EXPECT_FALSE(fs::exists(scratch.path() / "fine.png"));  // checking creates nothing that stays
  EXPECT_TRUE(fs::is_empty(scratch.path()));
}

TEST(AtomicFile, StaleTemporariesOfEndedProcessesAreRemovedOnTheNextWrite) {
  ScratchDirectory scratch("candela-atomic");
  const fs::path target = scratch.path() / "out.png";
  const fs::path other = scratch.path() / "other.png";
  const std::string own = fs::path(temporary_path_for(target.string())).filename().string();
  const std::string suffix = own.substr(own.find('-', 5) + 1);  // "HASH.png"
  const std::string other_own = fs::path(temporary_path_for(other.string())).filename().string();
  const std::string other_suffix = other_own.substr(other_own.find('-', 5) + 1);
  const pid_t ended = ended_process_id();
  // Left by a run killed while writing out.png; by a live process (our parent) writing it now; by
  // the ended run writing another file; and a file that only looks similar.
  const fs::path stale = scratch.path() / (".tmp-" + std::to_string(ended) + "-" + suffix);
  const fs::path live = scratch.path() / (".tmp-" + std::to_string(::getppid()) + "-" + suffix);
  const fs::path another = scratch.path() / (".tmp-" + std::to_string(ended) + "-" + other_suffix);
  const fs::path unrelated = scratch.path() / ".tmp-notes.txt";
  for (const fs::path& path : {stale, live, another, unrelated}) std::ofstream(path) << "half";
  write_text_atomically(target.string(), "whole");
  EXPECT_EQ(read_all(target), "whole");
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(another));  // cleaned when other.png is written, not before
  EXPECT_TRUE(fs::exists(unrelated));
  write_text_atomically(other.string(), "whole too");
  EXPECT_FALSE(fs::exists(another));
}

}  // namespace
}  // namespace candela
