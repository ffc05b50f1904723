#version 450 core
// shadow map pass: depth only
void main() {}
