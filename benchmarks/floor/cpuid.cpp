// The no-libc floor (no_libc.cpp) plus the 41 `cpuid` instructions that glibc's static start
// executes on the development VM (an AMD EPYC), leaf and subleaf in its order: its
// init_cpu_features (leaves 0, 1, 7, 0xd and the 0x8000000x) and its cache sizes, whose
// handle_amd asks 0x80000000 again before each of its 11 questions of 0x80000005 and 0x80000006.
// Counted by single-stepping an empty static program and the dispcon command (the same 41 in
// both; docs/performance.md, "Issue 14, twelfth round: the whole process"). In a virtual machine
// each one traps to the hypervisor: against BM_Command_Floor/no_libc, what they cost a process.
#if defined(__x86_64__)
namespace {
struct Leaf {
  unsigned eax, ecx;
};
constexpr Leaf kLeaves[] = {
    {0, 0},          {0x1, 0},        {0x7, 0},        {0x7, 1},        {0xd, 1},
    {0x80000000, 0}, {0x80000001, 0}, {0x80000007, 0}, {0x80000008, 0}, {0xd, 0},
    {0xd, 2},        {0xd, 3},        {0xd, 5},        {0xd, 6},        {0xd, 7},
    {0x80000000, 0}, {0x80000005, 0}, {0x80000000, 0}, {0x80000006, 0}, {0x80000000, 0},
    {0x80000006, 0}, {0x80000000, 0}, {0x80000005, 0}, {0x80000000, 0}, {0x80000005, 0},
    {0x80000000, 0}, {0x80000005, 0}, {0x80000000, 0}, {0x80000005, 0}, {0x80000000, 0},
    {0x80000006, 0}, {0x80000000, 0}, {0x80000006, 0}, {0x80000000, 0}, {0x80000006, 0},
    {0x80000000, 0}, {0x80000006, 0}, {0x80000000, 0}, {0x80000008, 0}, {0x1, 0},
    {0x8000001d, 3}};
static_assert(sizeof kLeaves / sizeof kLeaves[0] == 41, "glibc's 41");
}  // namespace

extern "C" [[noreturn]] void _start() {
  for (const Leaf& l : kLeaves) {
    unsigned a = l.eax, b, c = l.ecx, d;
    asm volatile("cpuid" : "+a"(a), "=b"(b), "+c"(c), "=d"(d));
  }
  // exit_group(0)
  asm volatile("mov $231, %%eax\n\txor %%edi, %%edi\n\tsyscall" ::: "rax", "rdi", "memory");
  __builtin_unreachable();
}
#else
#error "cpuid.cpp is the x86-64 floor only"
#endif
