"""The instructor's tools, kept apart from ``ddg``, which students read: the student edition
(``python -m instructor.edition``, run by ``make student``) and grading a class
(``python -m instructor.grade``). Neither is copied into the student edition."""
