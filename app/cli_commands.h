#pragma once
// The sublift-cli commands. Each returns the process exit code (0 ok); they throw
// cli::UsageError for bad usage and sublift::Error for bad input.
namespace sublift::cli {

int run_info(int argc, char** argv);
int run_render(int argc, char** argv);
int run_convert(int argc, char** argv);

}  // namespace sublift::cli
