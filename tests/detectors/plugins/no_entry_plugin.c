/* A shared library that is no moorsim plugin: it exports neither entry point. */
int not_a_plugin(void);
int not_a_plugin(void) { return 0; }
