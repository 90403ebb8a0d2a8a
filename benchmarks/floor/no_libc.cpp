// The floor of any process on this machine (benchmarks/io.cpp, BM_Command_Floor/no_libc): a
// program that does nothing but exit, with no C library and no dynamic loader (linked with
// -nostdlib -static). What its spawn costs is the kernel's exec, the first touch of its one
// page of code, and its exit: what every command, ours or another, pays before it runs a line.
#if defined(__x86_64__)
extern "C" [[noreturn]] void _start() {
  // exit_group(0)
  asm volatile("mov $231, %%eax\n\txor %%edi, %%edi\n\tsyscall" ::: "rax", "rdi", "memory");
  __builtin_unreachable();
}
#elif defined(__aarch64__)
extern "C" [[noreturn]] void _start() {
  // exit_group(0)
  asm volatile("mov x8, #94\n\tmov x0, #0\n\tsvc #0" ::: "x0", "x8", "memory");
  __builtin_unreachable();
}
#else
#error "no_libc.cpp knows the exit system call of x86-64 and AArch64 only"
#endif
