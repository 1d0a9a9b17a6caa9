// Linked with every object of one component (tests/components/CMakeLists.txt): building it is the check.
int main() { return 0; }
