#pragma once
// A run stopped by SIGINT (Ctrl-C), SIGTERM or SIGHUP leaves no staging folder behind: the
// earlier results stay as they were, and the checkpoints of a run that writes them stay too,
// so that `mfree run SCENE --restart FOLDER.checkpoints` continues it.
//
// The signal's handler passes it through a pipe to a thread of its own (a handler may do
// next to nothing safely), which removes the staging folders (io/staged_folder.hpp), says so
// on standard error, and ends the process by the same signal with its default action: the
// exit status is the conventional one (a shell shows 128 + the signal number: 130 for
// SIGINT, 143 for SIGTERM). A signal that was ignored when the program started (nohup, a
// background job without job control) stays ignored. A child process (the gmsh reader)
// resets the three to their default action.

namespace mfree {

/// Takes over SIGINT, SIGTERM and SIGHUP as above; call it first in main. Error when the pipe
/// cannot be made.
void remove_staging_folders_on_signals();

}  // namespace mfree
