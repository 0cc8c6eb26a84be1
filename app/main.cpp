#include "app/cli.hpp"

int main(int argc, char** argv) { return pronk::app::run_cli(argc, argv); }
