// The program of the layers' check (CMakeLists.txt): it runs nothing; its link is the check.
int main() { return 0; }
