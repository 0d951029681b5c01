# expect: - (whole file: no camera line)
sphere 0 0 0 1
