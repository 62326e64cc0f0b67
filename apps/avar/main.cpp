#include <iostream>

#include "avar/cli.hpp"

int main(int argc, char** argv) { return avar::app::run_cli(argc, argv, std::cout, std::cerr); }
