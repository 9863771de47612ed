// File outputs that never destroy what the user has.
//
// PendingOutputFile writes to a temporary file beside its target and renames it into place only
// when the command commits, so a run that fails (unusable input, write error) leaves an existing
// file as it was; a run that wrote its output whole but did not succeed (damaged input) keeps it
// beside the target as TARGET.partial (keep_beside). Targets that are not regular files (/dev/null,
// a FIFO, a terminal) are written directly: they cannot be replaced by a rename and hold nothing to
// lose. "-" is standard output.
//
// check_not_an_input() refuses an output that is one of the inputs (compared by device and inode,
// so symbolic and hard links are seen through).
#pragma once

#include <cstdio>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace dpscope {

class PendingOutputFile {
  public:
    // Opens `path` for writing ("-": standard output). The error names the file and the reason.
    static Result<std::unique_ptr<PendingOutputFile>> open(const std::string& path);
    ~PendingOutputFile();
    PendingOutputFile(const PendingOutputFile&) = delete;
    PendingOutputFile& operator=(const PendingOutputFile&) = delete;

    // The stream to write. Whoever closes it (a capture writer does) calls release_file() first.
    FILE* file() const noexcept { return file_; }
    void release_file() noexcept { file_ = nullptr; }
    // "<stdout>" or the path as the user gave it.
    const std::string& name() const noexcept { return name_; }
    bool is_stdout() const noexcept { return to_stdout_; }
    // Written to a temporary file that commit() renames (false for stdout and devices).
    bool is_staged() const noexcept { return !temporary_.empty(); }
    // What a failed write leaves, to follow its message: "; the file is left as it was" (or
    // "; no file is made" when there was none) when staged, else "".
    std::string_view left_as_it_was() const noexcept {
        if (!is_staged()) return "";
        return target_existed_ ? "; the file is left as it was" : "; no file is made";
    }

    // Closes the stream (unless released) and moves the temporary file into place. An error
    // when the close or the rename failed; the target is then as it was.
    Result<void> commit();
    // Closes the stream and moves the temporary file to TARGET.partial beside the target, which
    // stays as it was; an existing TARGET.partial is replaced. Returns that path ("" for stdout
    // and devices, written directly); an error when the close or the rename failed, or when
    // that path is one of `inputs` (the temporary file is then removed).
    Result<std::string> keep_beside(const std::vector<std::string>& inputs);
    // Closes and removes the temporary file; the target stays as it was. The destructor does
    // this when commit() was not called.
    void discard() noexcept;
    // A file was at the target when open() ran (the file a commit replaces).
    bool target_existed() const noexcept { return target_existed_; }

    // For a handler of a signal that ends the process: removes every temporary file of this
    // process's outputs not yet committed or discarded (their targets stay as they were).
    // Async-signal-safe. The first staged output installs a handler that does this and then ends
    // the process by the signal, for SIGINT, SIGTERM, SIGHUP, SIGQUIT and SIGPIPE where their
    // action is the default one; a command that handles one of them itself (sniff) calls this
    // where its handler ends the process.
    static void remove_all_after_signal() noexcept;

  private:
    PendingOutputFile() = default;
    // Closes the stream (flushes standard output); on failure removes the temporary file.
    Result<void> close_stream();
    FILE* file_ = nullptr;
    std::string name_;
    std::string target_;     // where commit() renames to ("" when written directly)
    std::string temporary_;  // the temporary file ("" when written directly)
    bool to_stdout_ = false;
    bool target_existed_ = false;
    bool done_ = false;
    int slot_ = -1;  // where remove_all_after_signal() finds the temporary file (-1: nowhere)
};

// The path of the file `path` names once the symbolic links of its last component are followed,
// whether or not that file exists (a link's relative target is read from the link's folder);
// `path` itself when it is no link. A loop of links ends after 40 of them.
std::string link_target(const std::string& path);

// Do paths `a` and `b` name the same file? By device and inode when both exist (so links are
// seen through, and devices compare too); otherwise by their canonical paths after following
// links, also links to a file that does not exist yet (a report file linked to the capture sniff
// is about to write).
bool same_file(const std::string& a, const std::string& b);

// An error when `output` is one of `inputs` (naming `output_option`, the file and the input).
// "-" as an input is standard input and as the output standard output; a path that does not
// exist yet is no input.
Result<void> check_not_an_input(const std::vector<std::string>& inputs, const std::string& output,
                                std::string_view output_option);

}  // namespace dpscope
