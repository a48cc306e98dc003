"""The public faces' formats: text, JSON and JUnit results, result files, compare."""
