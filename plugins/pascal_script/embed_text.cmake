# cmake -DIN=file -DOUT=file.cpp -P embed_text.cmake: IN's text as a C++ string constant.
file(READ ${IN} text)
file(WRITE ${OUT} "// Generated from ${IN} by embed_text.cmake: do not edit.\n"
  "namespace s2sim::pascal {\nextern const char* const kSupportUnitSource;\n"
  "const char* const kSupportUnitSource = R\"S2SIMPAS(${text})S2SIMPAS\";\n}\n")
