/* A file with no shader in it (only this comment): the error named "<command line>", the
   preprocessor's name for -D macros, instead of the file. */
