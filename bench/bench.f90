program veslide_bench
end program
