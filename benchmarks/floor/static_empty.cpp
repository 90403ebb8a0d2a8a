// An empty C++ program linked as the dispcon command is (statically where it can be): the floor
// of a process that starts the C library (benchmarks/io.cpp, BM_Command_Floor/static_empty).
// Against BM_Command_Floor/no_libc, what glibc's own start and exit cost.
int main() {
  return 0;
}
