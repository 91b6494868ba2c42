// Types only: see three-augment.d.ts. Importing this module does nothing at run time.
export {};
