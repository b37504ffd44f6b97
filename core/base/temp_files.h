#pragma once
// Temporary files of saves in flight (write_file_atomic), so that an interrupted save leaves
// nothing behind: SIGINT and SIGTERM unlink every registered file, then end the process as the
// signal would have (or pass it to the handler installed before ours).
//
// The handler runs in signal context, so the registry is a fixed array of fixed-size path
// buffers with an atomic state per slot: no allocation, no locks, only unlink(2), sigaction(2)
// and raise(3), which are async-signal-safe. A path too long for a slot, or a save beyond the
// slots in flight at once, is simply not registered (the save itself still works).
#include <cstddef>
#include <string>

namespace sublift {

/// Installs the SIGINT/SIGTERM cleanup once per process (later calls do nothing). A signal the
/// process ignores stays ignored.
void install_interrupt_cleanup();

/// Registers `path` for removal on SIGINT/SIGTERM; returns its slot, or -1 when not registered.
int register_temp_file(const std::string& path);

/// Forgets a slot from register_temp_file (after the file was renamed or removed); -1 is ignored.
void unregister_temp_file(int slot);

/// True when `path` is registered by this process (a save of this process is writing it).
bool is_registered_temp_file(const std::string& path);

/// The temporary name of the n-th save of this process: "NAME.tmp-PID-N".
std::string temp_file_name(const std::string& name, unsigned long n);

/// Removes leftovers of earlier saves of `target` beside it (core/base/file_io.h explains when
/// a leftover is stale); returns how many were removed. Errors are ignored: it is a tidy-up.
std::size_t remove_stale_temp_files(const std::string& target);

}  // namespace sublift
