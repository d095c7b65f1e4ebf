"""docs/tutorial/*.md: the numbers in the chapters' prose, from the commands each chapter runs."""
